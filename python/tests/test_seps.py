"""S_eps fusion against numpy saturation and Bayes' rule."""
import math

import numpy as np
import pytest

import intgrid


def bayes(p, q):
    return p * q / (p * q + (1.0 - p) * (1.0 - q))


@pytest.mark.parametrize("max_index", [127, 31, 1])
def test_fuse_indices_is_numpy_saturating_addition_for_every_int8_pair(max_index):
    values = np.arange(-max_index, max_index + 1, dtype=np.int8)
    a, b = np.meshgrid(values, values, indexing="ij")
    fused = intgrid.fuse_indices(a, b, max_index)
    expected = np.clip(a.astype(np.int64) + b.astype(np.int64), -max_index, max_index)
    assert fused.dtype == np.int8
    assert fused.shape == a.shape
    np.testing.assert_array_equal(fused, expected)
    # Saturation happened somewhere (the case is not trivially in range).
    assert (np.abs(a.astype(int) + b) > max_index).any()


def test_fuse_indices_int16_and_non_contiguous_inputs():
    rng = np.random.default_rng(7)
    a = rng.integers(-2000, 2001, size=(40, 30)).astype(np.int16)
    b = rng.integers(-2000, 2001, size=(30, 40)).astype(np.int16).T  # a transposed view
    fused = intgrid.fuse_indices(a, b, 1023)
    assert fused.dtype == np.int16
    np.testing.assert_array_equal(fused, np.clip(a.astype(int) + b, -1023, 1023))


def test_fuse_indices_rejects_bad_shapes_and_max_index():
    a = np.zeros(4, np.int8)
    with pytest.raises(ValueError, match="shapes differ"):
        intgrid.fuse_indices(a, np.zeros(5, np.int8), 127)
    with pytest.raises(ValueError, match="max_index"):
        intgrid.fuse_indices(a, a, 128)


@pytest.mark.parametrize("bits,eps", [(8, 0.0066), (8, 0.05), (4, 0.2), (12, 0.001)])
def test_codec_fusion_is_bayes_rule_inside_the_range(bits, eps):
    codec = intgrid.SepsCodec(bits, eps)
    assert codec.max_index == 2 ** (bits - 1) - 1
    assert codec.lambda_ == pytest.approx(math.log((0.5 + eps) / (0.5 - eps)), rel=1e-12)
    rng = np.random.default_rng(bits)
    half = codec.max_index // 2
    for a, b in rng.integers(-half, half + 1, size=(200, 2)):
        fused = codec.fuse(int(a), int(b))
        assert fused == a + b
        assert codec.probability(fused) == pytest.approx(
            bayes(codec.probability(int(a)), codec.probability(int(b))), rel=1e-10)
    # Past the range it saturates.
    assert codec.fuse(codec.max_index, 1) == codec.max_index
    assert codec.fuse(-codec.max_index, -codec.max_index) == -codec.max_index


def test_probability_is_the_logistic_of_n_lambda_vectorized():
    codec = intgrid.SepsCodec.for_levels(8, 0.604, 16)
    n = np.arange(-127, 128)
    p = codec.probability(n)
    np.testing.assert_allclose(p, 1.0 / (1.0 + np.exp(-n * codec.lambda_)), rtol=1e-13)
    assert codec.probability(16) == pytest.approx(0.604, rel=1e-12)  # p_levels = Pmax


def test_quantize_conservative_never_overstates_and_is_the_largest_such_index():
    codec = intgrid.SepsCodec(8, 0.01)
    for p in np.linspace(0.001, 0.999, 997):
        n = int(codec.quantize_conservative(p))
        pn = codec.probability(n)
        # Between 1/2 and p ...
        assert min(0.5, p) - 1e-15 <= pn <= max(0.5, p) + 1e-15
        # ... and one more step would pass p (unless saturated).
        if abs(n) < codec.max_index:
            step = 1 if p >= 0.5 else -1
            further = codec.probability(n + step)
            assert (further > p) if p >= 0.5 else (further < p)
    assert codec.quantize_conservative(float("nan")) == 0
    assert codec.quantize_nearest(1.0) == codec.max_index
    assert codec.quantize_nearest(0.0) == -codec.max_index


def test_fuse_probabilities_scalar_and_arrays():
    assert intgrid.fuse_probabilities(0.7, 0.8) == pytest.approx(bayes(0.7, 0.8), rel=1e-15)
    assert intgrid.fuse_probabilities(1.0, 0.0) == 0.5  # contradicting certainties
    rng = np.random.default_rng(3)
    p, q = rng.uniform(0.01, 0.99, size=(2, 17, 5))
    np.testing.assert_allclose(intgrid.fuse_probabilities(p, q), bayes(p, q), rtol=1e-14)
    with pytest.raises(ValueError, match="shapes differ"):
        intgrid.fuse_probabilities(p, q[:3])


def test_bad_codec_parameters_raise_value_error_with_a_message():
    with pytest.raises(ValueError, match="index width must be 2..16 bits, got 17"):
        intgrid.SepsCodec(17, 0.1)
    with pytest.raises(ValueError, match="eps must lie in"):
        intgrid.SepsCodec(8, 0.5)
    with pytest.raises(ValueError, match="Pmax"):
        intgrid.SepsCodec.for_levels(8, 0.4, 16)


def test_ugamma_fusion_matches_bayes_within_its_rounding():
    u = intgrid.UGamma(16, 16)
    for p, q in [(0.7, 0.8), (0.3, 0.9), (0.55, 0.45)]:
        fused = u.to_probability(u.fuse(u.from_probability(p), u.from_probability(q)))
        assert fused == pytest.approx(bayes(p, q), abs=0.05)
    assert u.to_probability(u.multiply(u.from_probability(0.5), u.from_probability(0.5))) == \
        pytest.approx(0.25, rel=0.05)
