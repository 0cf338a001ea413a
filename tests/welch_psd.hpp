#pragma once

// Welch's estimate of a one-sided power spectral density, for the tests of the disturbance
// generators (docs/model.md §15). Convention: for a real sequence x_k sampled at f_s, the one-sided
// PSD G(f) on 0 <= f <= f_s / 2 integrates to the variance (∫ G df = σ²); a white sequence of
// variance σ² has G = 2 σ² / f_s. Segments of a power-of-two length, Hann window, 50 % overlap,
// each segment's mean removed.

#include <cmath>
#include <complex>
#include <cstddef>
#include <numbers>
#include <vector>

namespace thetad::testing {

// In-place radix-2 FFT (the length must be a power of two).
inline void fft(std::vector<std::complex<double>>& a) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (std::size_t length = 2; length <= n; length <<= 1) {
    const double angle = -2.0 * std::numbers::pi / static_cast<double>(length);
    const std::complex<double> step(std::cos(angle), std::sin(angle));
    for (std::size_t start = 0; start < n; start += length) {
      std::complex<double> w(1.0);
      for (std::size_t k = 0; k < length / 2; ++k, w *= step) {
        const std::complex<double> even = a[start + k], odd = w * a[start + k + length / 2];
        a[start + k] = even + odd;
        a[start + k + length / 2] = even - odd;
      }
    }
  }
}

struct Spectrum {
  double resolution = 0.0;   // Hz between bins: f_s / segment
  std::vector<double> psd;   // one-sided, bins 0 ... segment / 2
  int segments = 0;

  double frequency(std::size_t bin) const { return resolution * static_cast<double>(bin); }
  // The mean of the PSD over the bins in [low, high] Hz, and of `model(f)` over the same bins.
  template <class Model>
  std::pair<double, double> band_means(double low, double high, Model model) const {
    double estimated = 0.0, specified = 0.0;
    int bins = 0;
    for (std::size_t k = 0; k < psd.size(); ++k) {
      const double f = frequency(k);
      if (f < low || f > high) continue;
      estimated += psd[k];
      specified += model(f);
      ++bins;
    }
    return {estimated / bins, specified / bins};
  }
};

// Welch's estimate of `x` sampled at `rate` (Hz) with segments of `segment` samples (a power of two).
inline Spectrum welch_psd(const std::vector<double>& x, double rate, std::size_t segment) {
  std::vector<double> window(segment);
  double window_power = 0.0;
  for (std::size_t i = 0; i < segment; ++i) {
    window[i] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(segment));
    window_power += window[i] * window[i];
  }
  Spectrum spectrum;
  spectrum.resolution = rate / static_cast<double>(segment);
  spectrum.psd.assign(segment / 2 + 1, 0.0);
  std::vector<std::complex<double>> buffer(segment);
  for (std::size_t start = 0; start + segment <= x.size(); start += segment / 2) {
    double mean = 0.0;
    for (std::size_t i = 0; i < segment; ++i) mean += x[start + i];
    mean /= static_cast<double>(segment);
    for (std::size_t i = 0; i < segment; ++i) buffer[i] = window[i] * (x[start + i] - mean);
    fft(buffer);
    for (std::size_t k = 0; k < spectrum.psd.size(); ++k) {
      // Two-sided |X|² / (f_s Σw²), doubled except at 0 and f_s / 2.
      const double side = (k == 0 || k == segment / 2) ? 1.0 : 2.0;
      spectrum.psd[k] += side * std::norm(buffer[k]) / (rate * window_power);
    }
    ++spectrum.segments;
  }
  for (double& value : spectrum.psd) value /= spectrum.segments;
  return spectrum;
}

}  // namespace thetad::testing
