"""The narrow and sectoral ISMs against brute-force Bayes written here in numpy."""
import math

import numpy as np
import pytest

import intgrid


def gaussian(error, sigma):
    return np.exp(-0.5 * (error / sigma) ** 2) / (sigma * math.sqrt(2.0 * math.pi))


def configurations(n):
    """Every occupancy configuration of n cells but the empty one: (g, bits[g, i])."""
    g = np.arange(1, 2 ** n, dtype=np.int64)
    bits = (g[:, None] >> np.arange(n)) & 1
    return g, bits.astype(bool)


def brute_force_narrow(sigma0, k_d, z, cell, n):
    """P(o_i | z) by Bayes over all 2^n configurations, priors 1/2: the likelihood of a
    configuration is p(z | distance of its nearest occupied cell), nothing for the empty one."""
    g, bits = configurations(n)
    nearest = np.log2(g & -g).round().astype(int) + 1  # lowest set bit, 1-based
    d = nearest * cell
    likelihood = gaussian(z - d, sigma0 * (1.0 + k_d * d))
    return (bits * likelihood[:, None]).sum(axis=0) / likelihood.sum()


@pytest.mark.parametrize("n,sigma0,k_d,z,cell", [
    (1, 0.05, 0.0, 0.05, 0.05),
    (6, 0.05, 0.0, 0.17, 0.05),
    (10, 0.03, 0.0, 0.26, 0.05),
    (12, 0.02, 0.5, 0.33, 0.04),
    (9, 0.2, 0.0, 0.9, 0.1),   # wide sigma: the ISM is far from certain anywhere
    (8, 0.05, 0.0, 0.9, 0.05),  # the reading past the cells: everything trends empty
])
def test_narrow_ism_equals_brute_force_bayes(n, sigma0, k_d, z, cell):
    model = intgrid.GaussianBeamModel(sigma0, k_d)
    ism = intgrid.narrow_ism(model, z, cell, n)
    assert ism.shape == (n,) and ism.dtype == np.float64
    np.testing.assert_allclose(ism, brute_force_narrow(sigma0, k_d, z, cell, n), rtol=0, atol=1e-12)


def test_narrow_ism_shape_free_before_occupied_at_unknown_after():
    model = intgrid.GaussianBeamModel(0.05)
    cell, z, n = 0.05, 2.0, 80
    ism = intgrid.narrow_ism(model, z, cell, n)
    k_z = round(z / cell)  # cell 40 holds the reading
    assert np.all(ism[: k_z - 6] < 1e-6)  # well before z: empty
    assert np.all(np.abs(ism[k_z + 10:] - 0.5) < 1e-9)  # well past z: no information
    peak = int(np.argmax(ism)) + 1
    assert abs(peak - k_z) <= 1 and ism[peak - 1] > 0.5
    assert peak == intgrid.predicted_argmax_cell(model, z, cell, n)
    # The peak is the Pmax of the resolution analysis (z on a cell centre).
    assert ism[peak - 1] == pytest.approx(intgrid.narrow_pmax(cell, 0.05), abs=1e-9)


def brute_force_sectoral(model, grid, z):
    """P(o | z) per polar cell by Bayes over all 2^(rings*bins) configurations: the likelihood
    is the cone model's Gaussian at the nearest occupied ring, its sigma widened by the occupied
    sectors of that ring (theta of the one nearest the axis, and their number)."""
    n = grid.rings * grid.bins
    g, bits = configurations(n)
    cells = bits.reshape(len(g), grid.rings, grid.bins)
    ring_occupied = cells.any(axis=2)
    ring = ring_occupied.argmax(axis=1)  # 0-based nearest occupied ring
    nearest = cells[np.arange(len(g)), ring]  # (configs, bins)
    per = grid.bins // grid.sectors
    sectors = nearest.reshape(len(g), grid.sectors, per).any(axis=2)
    size = sectors.sum(axis=1)
    rank = np.abs(2 * np.arange(grid.sectors) + 1 - grid.sectors)
    theta = np.where(sectors, rank, grid.sectors).min(axis=1) / grid.sectors
    d = (ring + 1) * grid.cell
    sigma = (model.sigma0 * (1 + model.k_d * d) * (1 + model.k_theta * theta)
             * (1 + model.k_size / size) / (1 + model.k_size))
    likelihood = gaussian(z - d, sigma)
    p = (bits * likelihood[:, None]).sum(axis=0) / likelihood.sum()
    return p.reshape(grid.rings, grid.bins)


@pytest.mark.parametrize("rings,bins,sectors,z", [
    (3, 4, 2, 0.1), (3, 4, 2, 0.125), (2, 6, 3, 0.06), (3, 4, 4, 0.14), (4, 3, 1, 0.1),
])
def test_sectoral_ism_equals_brute_force_bayes(rings, bins, sectors, z):
    model = intgrid.ConeSensorModel(sigma0=0.02, k_d=0.05, k_theta=0.5, k_size=0.5)
    grid = intgrid.SectoralGrid(fov=math.radians(30), rings=rings, bins=bins, sectors=sectors,
                                cell=0.05)
    ism = intgrid.sectoral_ism(model, grid, z)
    assert ism.shape == (rings, bins)
    expected = brute_force_sectoral(model, grid, z)
    np.testing.assert_allclose(ism, expected, rtol=0, atol=1e-12)
    # Not a trivial case: some cell is confidently occupied or empty.
    assert np.abs(expected - 0.5).max() > 0.02


def test_ism_errors_are_value_errors_with_messages():
    with pytest.raises(ValueError, match="cell must be a positive"):
        intgrid.narrow_ism(intgrid.GaussianBeamModel(0.05), 1.0, 0.0, 10)
    with pytest.raises(ValueError, match="sigma must be a positive"):
        intgrid.narrow_ism(intgrid.GaussianBeamModel(-1.0), 1.0, 0.05, 10)
    with pytest.raises(ValueError, match="z must be finite"):
        intgrid.narrow_ism(intgrid.GaussianBeamModel(0.05), float("nan"), 0.05, 10)
    with pytest.raises(ValueError, match="multiple of sectors"):
        intgrid.sectoral_ism(intgrid.ConeSensorModel(), intgrid.SectoralGrid(bins=6, sectors=4),
                             1.0)
