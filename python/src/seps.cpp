// S_eps and U_gamma in Python.
#include "bindings.hpp"

namespace intgrid::python {
namespace {

template <class Index>
py::array_t<Index> fuse_index_arrays(const py::array_t<Index, py::array::c_style>& a,
                                     const py::array_t<Index, py::array::c_style>& b,
                                     int max_index) {
  if (max_index < 1 || max_index > std::numeric_limits<Index>::max())
    value_error("max_index must be 1.." + std::to_string(std::numeric_limits<Index>::max()) +
                " for this dtype, got " + std::to_string(max_index));
  if (a.ndim() != b.ndim() || !std::equal(a.shape(), a.shape() + a.ndim(), b.shape()))
    value_error("fuse_indices: the arrays' shapes differ");
  py::array_t<Index> out(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()));
  const auto n = static_cast<std::size_t>(a.size());
  core::fuse_indices<Index>(std::span<const Index>(a.data(), n),
                            std::span<const Index>(b.data(), n),
                            std::span<Index>(out.mutable_data(), n), max_index);
  return out;
}

}  // namespace

void bind_seps(py::module_& m) {
  m.def("logit", &core::logit, "p"_a);
  m.def("logistic", &core::logistic, "x"_a);
  m.def("max_index_for_bits", &core::max_index_for_bits,
        "2^(bits-1) - 1; raises ValueError unless 2 <= bits <= 16.", "bits"_a);

  py::class_<core::SepsCodec>(m, "SepsCodec",
                              "S_eps indices of `bits` bits: p_n has log-odds n * lambda, "
                              "lambda = logit(1/2 + eps); fusion is saturating addition.")
      .def(py::init<int, double>(), "bits"_a, "eps"_a)
      .def_static("for_confidence", &core::SepsCodec::for_confidence,
                  "eps such that p_max_index equals p_most.", "bits"_a, "p_most"_a)
      .def_static("for_levels", &core::SepsCodec::for_levels, "eps such that p_levels equals pmax.",
                  "bits"_a, "pmax"_a, "levels"_a)
      .def_property_readonly("bits", &core::SepsCodec::bits)
      .def_property_readonly("eps", &core::SepsCodec::eps)
      .def_property_readonly("lambda_", &core::SepsCodec::lambda, "logit(1/2 + eps)")
      .def_property_readonly("max_index", &core::SepsCodec::max_index)
      .def("probability",
           py::vectorize([](const core::SepsCodec* c, int n) { return c->probability(n); }),
           "p_n (vectorized over arrays).", "n"_a)
      .def("quantize_conservative", py::vectorize([](const core::SepsCodec* c, double p) {
             return c->quantize_conservative(p);
           }),
           "The index of largest magnitude never more confident than p (vectorized).", "p"_a)
      .def("quantize_nearest",
           py::vectorize([](const core::SepsCodec* c, double p) { return c->quantize_nearest(p); }),
           "The index nearest p in log-odds (vectorized).", "p"_a)
      .def("fuse",
           py::vectorize([](const core::SepsCodec* c, int a, int b) { return c->fuse(a, b); }),
           "Saturating index addition (vectorized).", "a"_a, "b"_a)
      .def("__repr__", [](const core::SepsCodec& c) {
        return "SepsCodec(bits=" + std::to_string(c.bits()) + ", eps=" + number(c.eps()) + ")";
      });

  m.def("fuse_indices", &fuse_index_arrays<std::int8_t>, "a"_a, "b"_a, "max_index"_a);
  m.def("fuse_indices", &fuse_index_arrays<std::int16_t>,
        "Cell-wise saturating addition of two int8 (or int16) index arrays of one shape: "
        "clip(a + b, -max_index, max_index).",
        "a"_a, "b"_a, "max_index"_a);

  m.def("fuse_probabilities", py::overload_cast<double, double>(&core::fuse_probabilities), "p"_a,
        "q"_a);
  m.def(
      "fuse_probabilities",
      [](const CArray<double>& p, const CArray<double>& q) {
        if (p.ndim() != q.ndim() || !std::equal(p.shape(), p.shape() + p.ndim(), q.shape()))
          value_error("fuse_probabilities: the arrays' shapes differ");
        py::array_t<double> out(std::vector<py::ssize_t>(p.shape(), p.shape() + p.ndim()));
        const auto n = static_cast<std::size_t>(p.size());
        core::fuse_probabilities(std::span<const double>(p.data(), n),
                                 std::span<const double>(q.data(), n),
                                 std::span<double>(out.mutable_data(), n));
        return out;
      },
      "Bayesian fusion pq / (pq + (1-p)(1-q)) of two probabilities or two arrays of one shape.",
      "p"_a, "q"_a);

  py::class_<core::UGamma>(m, "UGamma",
                           "Probabilities as integer exponents u_n = gamma^n, gamma = "
                           "2^(-1/steps_per_halving).")
      .def(py::init<int, int>(), "bits"_a = 16, "steps_per_halving"_a = 16)
      .def_property_readonly("bits", &core::UGamma::bits)
      .def_property_readonly("steps_per_halving", &core::UGamma::steps_per_halving)
      .def_property_readonly("gamma", &core::UGamma::gamma)
      .def_property_readonly("zero", &core::UGamma::zero, "the code of probability 0")
      .def_property_readonly("min_index", &core::UGamma::min_index)
      .def("multiply", &core::UGamma::multiply, "i"_a, "j"_a)
      .def("divide", &core::UGamma::divide, "i"_a, "j"_a)
      .def("add", &core::UGamma::add, "i"_a, "j"_a)
      .def("complement", &core::UGamma::complement, "i"_a)
      .def("fuse", &core::UGamma::fuse, "i"_a, "j"_a)
      .def("from_probability", &core::UGamma::from_probability, "p"_a)
      .def("to_probability", &core::UGamma::to_probability, "i"_a)
      .def("from_log", &core::UGamma::from_log, "ln_u"_a)
      .def("to_log", &core::UGamma::to_log, "i"_a);
}

}  // namespace intgrid::python
