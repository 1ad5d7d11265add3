"""The benchmark metrics: relMSE with its epsilon, the reference noise floor, the
FLIP wrapper, and reading error-vs-time curves (no renderer, no peers)."""

import numpy as np
import pytest

from benchmarks.metrics import (
    RELMSE_EPSILON,
    error_at_time,
    flip,
    relmse,
    relmse_from_two_seeds,
    relmse_noise_floor,
    time_to_error,
)


def test_relmse_closed_form():
    reference = np.full((4, 5, 3), 2.0)
    image = reference + 0.5
    expected = 0.25 / (4.0 + RELMSE_EPSILON)
    assert relmse(image, reference) == pytest.approx(expected, rel=1e-12)


def test_relmse_epsilon_guards_black_pixels():
    reference = np.zeros((2, 2, 3))
    image = np.full((2, 2, 3), 0.1)
    assert relmse(image, reference) == pytest.approx(0.01 / RELMSE_EPSILON)
    assert relmse(image, reference, epsilon=1.0) == pytest.approx(0.01)


def test_relmse_rejects_mismatched_shapes():
    with pytest.raises(ValueError):
        relmse(np.zeros((2, 2, 3)), np.zeros((2, 3, 3)))
    with pytest.raises(ValueError):
        relmse(np.zeros((2, 2)), np.zeros((2, 2)))


def test_noise_floor_matches_expected_relmse_of_noisy_reference():
    rng = np.random.default_rng(3)
    truth = np.full((64, 64, 3), 0.5)
    sigma = 0.05
    noisy = truth + rng.normal(0.0, sigma, truth.shape)
    floor = relmse_noise_floor(truth, np.full(truth.shape, sigma**2))
    assert floor == pytest.approx(sigma**2 / (0.25 + RELMSE_EPSILON))
    # measured relMSE of a noisy image against the truth equals the floor statistically
    assert relmse(noisy, truth) == pytest.approx(floor, rel=0.05)


def test_two_seeds_estimate_the_relmse_of_known_noise_without_a_reference():
    """Pixels from dark (where eps decides) to bright, each with 8 % noise: two independent renders estimate the
    expected relMSE mean(sigma^2 / (mu^2 + eps)) of either, as the error of one against the truth measures it."""
    rng = np.random.default_rng(7)
    truth = rng.uniform(0.02, 2.0, (128, 128, 3))
    sigma = 0.08 * truth
    expected = float(np.mean(sigma**2 / (truth**2 + RELMSE_EPSILON)))
    first, second = (truth + rng.normal(0.0, 1.0, truth.shape) * sigma for _ in range(2))
    estimate = relmse_from_two_seeds(first, second)
    assert estimate == pytest.approx(expected, rel=0.03)
    assert estimate == pytest.approx(relmse(first, truth), rel=0.03)
    # half the deviation (four times the samples) is a quarter of the relMSE
    quieter = relmse_from_two_seeds(truth + (first - truth) / 2, truth + (second - truth) / 2)
    assert quieter == pytest.approx(estimate / 4, rel=0.01)


def test_flip_zero_for_identical_and_grows_with_noise():
    rng = np.random.default_rng(1)
    reference = rng.uniform(0.1, 1.0, (32, 32, 3))
    assert flip(reference, reference) == pytest.approx(0.0, abs=1e-6)
    small = flip(reference + rng.normal(0, 0.02, reference.shape), reference)
    large = flip(reference + rng.normal(0, 0.2, reference.shape), reference)
    assert 0.0 < small < large <= 1.0


def test_flip_tolerates_negative_and_nan_samples():
    reference = np.full((16, 16, 3), 0.5)
    image = reference.copy()
    image[0, 0] = -1.0
    image[1, 1] = np.nan
    assert 0.0 < flip(image, reference) < 1.0


def test_curve_interpolation_is_log_log():
    times = np.array([1.0, 4.0, 16.0])
    errors = 0.1 / times  # slope -1 in log-log
    value, extrapolated = error_at_time(times, errors, 2.0)
    assert value == pytest.approx(0.05) and not extrapolated
    value, extrapolated = error_at_time(times, errors, 64.0)
    assert value == pytest.approx(0.1 / 64.0) and extrapolated
    seconds, extrapolated = time_to_error(times, errors, 0.01)
    assert seconds == pytest.approx(10.0) and not extrapolated
    seconds, extrapolated = time_to_error(times, errors, 0.001)
    assert seconds == pytest.approx(100.0) and extrapolated


def test_time_to_error_nan_when_curve_never_falls():
    seconds, _ = time_to_error([1.0, 2.0], [0.1, 0.2], 0.01)
    assert np.isnan(seconds)
