#pragma once

// A'X + XA + Q = 0 for one N×N matrix A and a symmetric Q by Bartels–Stewart, in plain loops over
// row-major arrays: Householder reduction to Hessenberg form, Francis double-shift QR to the real
// Schur form A = U T U' (T quasi-triangular, 2×2 blocks for complex pairs), then the block sweep
// over T'Y + YT = −U'QU. It follows the library's LyapunovWorkspace (core/lyapunov.cpp: Eigen's
// HessenbergDecomposition and RealSchur, the same shifts, deflation tests and sweep) step for
// step, so that the exported SDRE step rounds as the library's does. No heap, no exceptions: a
// status. Standard C++ only; `thetad export` copies this file into the header it writes.

#ifndef THETAD_ONBOARD_LYAPUNOV_SCHUR
#define THETAD_ONBOARD_LYAPUNOV_SCHUR

#include <cmath>
#include <limits>

namespace thetad_onboard {

// Every buffer of a factorization and its solves.
template <class T, int N>
struct SchurWorkspace {
  T t[N * N], u[N * N];     // A = U T U'
  T y[N * N], scratch[N * N];
  T householder[N], work[N];
  T wr[N], wi[N];           // eigenvalues, in Schur order
  T a_norm;                 // ‖A‖_F: the singularity threshold of a solve
};

namespace schur_detail {

// v = [c0; tail] → H = I − tau [1; e][1; e]', H v = [beta; 0] (Eigen's makeHouseholder).
template <class T>
void make_householder(T c0, const T* tail, int count, T* essential, T& tau, T& beta) {
  T tail_squared = T(0);
  for (int i = 0; i < count; ++i) tail_squared += tail[i] * tail[i];
  if (tail_squared <= std::numeric_limits<T>::min()) {
    tau = T(0);
    beta = c0;
    for (int i = 0; i < count; ++i) essential[i] = T(0);
    return;
  }
  beta = std::sqrt(c0 * c0 + tail_squared);
  if (c0 >= T(0)) beta = -beta;
  for (int i = 0; i < count; ++i) essential[i] = tail[i] / (c0 - beta);
  tau = (beta - c0) / beta;
}

// Rows r0 … r0+len−1 of the columns c0 … c1−1 of M (N columns) = H · those rows.
template <class T, int N>
void householder_left(T* m, int r0, int len, int c0, int c1, const T* essential, T tau) {
  if (tau == T(0)) return;
  for (int c = c0; c < c1; ++c) {
    T sum = m[r0 * N + c];
    for (int i = 1; i < len; ++i) sum += essential[i - 1] * m[(r0 + i) * N + c];
    m[r0 * N + c] -= tau * sum;
    for (int i = 1; i < len; ++i) m[(r0 + i) * N + c] -= tau * essential[i - 1] * sum;
  }
}

// Columns c0 … c0+len−1 of the rows r0 … r1−1 of M = those columns · H.
template <class T, int N>
void householder_right(T* m, int c0, int len, int r0, int r1, const T* essential, T tau) {
  if (tau == T(0)) return;
  for (int r = r0; r < r1; ++r) {
    T sum = m[r * N + c0];
    for (int i = 1; i < len; ++i) sum += m[r * N + c0 + i] * essential[i - 1];
    m[r * N + c0] -= tau * sum;
    for (int i = 1; i < len; ++i) m[r * N + c0 + i] -= tau * sum * essential[i - 1];
  }
}

// T = Q'(A/scale)Q Hessenberg, U = Q: the reflectors are kept below T's subdiagonal until U is formed.
template <class T, int N>
void hessenberg(SchurWorkspace<T, N>& w) {
  T* a = w.t;
  for (int i = 0; i + 1 < N; ++i) {
    const int remaining = N - i - 1;
    T column[N], tau, beta;
    for (int r = 0; r < remaining; ++r) column[r] = a[(i + 1 + r) * N + i];
    make_householder(column[0], column + 1, remaining - 1, column + 1, tau, beta);
    a[(i + 1) * N + i] = beta;
    for (int r = 1; r < remaining; ++r) a[(i + 1 + r) * N + i] = column[r];
    w.householder[i] = tau;
    householder_left<T, N>(a, i + 1, remaining, i + 1, N, column + 1, tau);
    householder_right<T, N>(a, i + 1, remaining, 0, N, column + 1, tau);
  }
  // U = H_0 H_1 … H_{N−2}, applied from the last (Eigen's HouseholderSequence::evalTo).
  for (int e = 0; e < N * N; ++e) w.u[e] = T(0);
  for (int i = 0; i < N; ++i) w.u[i * N + i] = T(1);
  for (int i = N - 2; i >= 0; --i) {
    const int remaining = N - i - 1;
    T essential[N];
    for (int r = 1; r < remaining; ++r) essential[r - 1] = a[(i + 1 + r) * N + i];
    householder_left<T, N>(w.u, i + 1, remaining, i + 1, N, essential, w.householder[i]);
  }
  for (int c = 0; c + 2 < N; ++c)
    for (int r = c + 2; r < N; ++r) a[r * N + c] = T(0);
}

// The right side of entry (i, j) of the symmetric sweep with the known terms subtracted:
// Y_ij − Σ_{k<i0} T_ki Y_kj − Σ_{k<j0} Y_ki T_kj.
template <class T, int N>
T reduced(const SchurWorkspace<T, N>& w, int i, int j, int i0, int j0) {
  T column_terms = T(0), row_terms = T(0);
  for (int k = 0; k < i0; ++k) column_terms += w.t[k * N + i] * w.y[k * N + j];
  for (int k = 0; k < j0; ++k) row_terms += w.y[k * N + i] * w.t[k * N + j];
  return w.y[i * N + j] - column_terms - row_terms;
}

// Rows iu−1, iu have split off: a real pair is rotated to triangular form (Eigen's splitOffTwoRows).
template <class T, int N>
void split_off_two_rows(SchurWorkspace<T, N>& w, int iu, T exshift) {
  T* t = w.t;
  const T p = T(0.5) * (t[(iu - 1) * N + iu - 1] - t[iu * N + iu]);
  const T q = p * p + t[iu * N + iu - 1] * t[(iu - 1) * N + iu];
  t[iu * N + iu] += exshift;
  t[(iu - 1) * N + iu - 1] += exshift;
  if (q >= T(0)) {
    const T z = std::sqrt(std::abs(q));
    // Eigen's makeGivens(a, b): [c s; −s c]' [a; b] = [r; 0].
    const T a = p >= T(0) ? p + z : p - z, b = t[iu * N + iu - 1];
    T c, s;
    if (b == T(0)) {
      c = a < T(0) ? T(-1) : T(1);
      s = T(0);
    } else if (a == T(0)) {
      c = T(0);
      s = b < T(0) ? T(1) : T(-1);
    } else if (std::abs(a) > std::abs(b)) {
      const T ratio = b / a, root = std::sqrt(T(1) + ratio * ratio);
      c = T(1) / (a < T(0) ? -root : root);
      s = -ratio * c;
    } else {
      const T ratio = a / b, root = std::sqrt(T(1) + ratio * ratio);
      s = -T(1) / (b < T(0) ? -root : root);
      c = -ratio * s;
    }
    // Rows iu−1, iu (columns iu−1 …) by the rotation's adjoint, then columns iu−1, iu (rows … iu).
    for (int col = iu - 1; col < N; ++col) {
      const T x = t[(iu - 1) * N + col], y = t[iu * N + col];
      t[(iu - 1) * N + col] = c * x - s * y;
      t[iu * N + col] = s * x + c * y;
    }
    for (int row = 0; row <= iu; ++row) {
      const T x = t[row * N + iu - 1], y = t[row * N + iu];
      t[row * N + iu - 1] = c * x - s * y;
      t[row * N + iu] = s * x + c * y;
    }
    t[iu * N + iu - 1] = T(0);
    for (int row = 0; row < N; ++row) {
      const T x = w.u[row * N + iu - 1], y = w.u[row * N + iu];
      w.u[row * N + iu - 1] = c * x - s * y;
      w.u[row * N + iu] = s * x + c * y;
    }
  }
  if (iu > 1) t[(iu - 1) * N + iu - 2] = T(0);
}

// One Francis double-shift step on rows il … iu (Eigen's computeShift, initFrancisQRStep and
// performFrancisQRStep).
template <class T, int N>
void francis_step(SchurWorkspace<T, N>& w, int il, int iu, int iteration, T& exshift) {
  T* t = w.t;
  T shift[3] = {t[iu * N + iu], t[(iu - 1) * N + iu - 1], t[iu * N + iu - 1] * t[(iu - 1) * N + iu]};
  if (iteration == 10) {  // Wilkinson's exceptional shift
    exshift += shift[0];
    for (int i = 0; i <= iu; ++i) t[i * N + i] -= shift[0];
    const T s = std::abs(t[iu * N + iu - 1]) + std::abs(t[(iu - 1) * N + iu - 2]);
    shift[0] = shift[1] = T(0.75) * s;
    shift[2] = T(-0.4375) * s * s;
  }
  if (iteration == 30) {  // MATLAB's exceptional shift
    T s = (shift[1] - shift[0]) / T(2.0);
    s = s * s + shift[2];
    if (s > T(0)) {
      s = std::sqrt(s);
      if (shift[1] < shift[0]) s = -s;
      s = s + (shift[1] - shift[0]) / T(2.0);
      s = shift[0] - shift[2] / s;
      exshift += s;
      for (int i = 0; i <= iu; ++i) t[i * N + i] -= s;
      shift[0] = shift[1] = shift[2] = T(0.964);
    }
  }
  T v[3] = {T(0), T(0), T(0)};
  int im = iu - 2;
  for (; im >= il; --im) {
    const T tmm = t[im * N + im], r = shift[0] - tmm, s = shift[1] - tmm;
    v[0] = (r * s - shift[2]) / t[(im + 1) * N + im] + t[im * N + im + 1];
    v[1] = t[(im + 1) * N + im + 1] - tmm - r - s;
    v[2] = t[(im + 2) * N + im + 1];
    if (im == il) break;
    const T lhs = t[im * N + im - 1] * (std::abs(v[1]) + std::abs(v[2]));
    const T rhs = v[0] * (std::abs(t[(im - 1) * N + im - 1]) + std::abs(tmm) + std::abs(t[(im + 1) * N + im + 1]));
    if (std::abs(lhs) < std::numeric_limits<T>::epsilon() * rhs) break;
  }
  for (int k = im; k <= iu - 2; ++k) {
    const bool first = k == im;
    if (!first)
      for (int i = 0; i < 3; ++i) v[i] = t[(k + i) * N + k - 1];
    T essential[2], tau, beta;
    make_householder(v[0], v + 1, 2, essential, tau, beta);
    if (beta == T(0)) continue;
    if (first && k > il) t[k * N + k - 1] = -t[k * N + k - 1];
    else if (!first) t[k * N + k - 1] = beta;
    householder_left<T, N>(t, k, 3, k, N, essential, tau);
    householder_right<T, N>(t, k, 3, 0, (iu < k + 3 ? iu : k + 3) + 1, essential, tau);
    householder_right<T, N>(w.u, k, 3, 0, N, essential, tau);
  }
  T essential[1], tau, beta;
  make_householder(t[(iu - 1) * N + iu - 2], &t[iu * N + iu - 2], 1, essential, tau, beta);
  if (beta != T(0)) {
    t[(iu - 1) * N + iu - 2] = beta;
    householder_left<T, N>(t, iu - 1, 2, iu - 1, N, essential, tau);
    householder_right<T, N>(t, iu - 1, 2, 0, iu + 1, essential, tau);
    householder_right<T, N>(w.u, iu - 1, 2, 0, N, essential, tau);
  }
  // The bulge's trail below the subdiagonal is zero but for rounding: cleared.
  for (int i = im + 2; i <= iu; ++i) {
    t[i * N + i - 2] = T(0);
    if (i > im + 2) t[i * N + i - 3] = T(0);
  }
}

}  // namespace schur_detail

// The real Schur form of a (row-major N×N) into w, and its eigenvalues. At most 40 N QR sweeps
// (Eigen's cap): Status::schur_not_converged beyond.
template <class T, int N>
Status real_schur(const T* a, SchurWorkspace<T, N>& w) {
  T scale = T(0), squares = T(0);
  for (int e = 0; e < N * N; ++e) {
    if (!std::isfinite(a[e])) return Status::not_finite;
    scale = std::abs(a[e]) > scale ? std::abs(a[e]) : scale;
    squares += a[e] * a[e];
  }
  w.a_norm = std::sqrt(squares);
  for (int e = 0; e < N * N; ++e) w.t[e] = scale > T(0) ? a[e] / scale : T(0);
  schur_detail::hessenberg(w);
  T* t = w.t;
  T norm = T(0);
  for (int c = 0; c < N; ++c)
    for (int r = 0; r < N && r <= c + 1; ++r) norm += std::abs(t[r * N + c]);
  const T eps = std::numeric_limits<T>::epsilon();
  const T zero = norm * eps * eps > std::numeric_limits<T>::min() ? norm * eps * eps : std::numeric_limits<T>::min();
  int iu = N - 1, iteration = 0, total = 0;
  T exshift = T(0);
  while (norm != T(0) && iu >= 0) {
    int il = iu;  // the first row of the unreduced block that ends at iu
    while (il > 0) {
      T s = std::abs(t[(il - 1) * N + il - 1]) + std::abs(t[il * N + il]);
      s = s * eps > zero ? s * eps : zero;
      if (std::abs(t[il * N + il - 1]) <= s) break;
      --il;
    }
    if (il == iu) {
      t[iu * N + iu] += exshift;
      if (iu > 0) t[iu * N + iu - 1] = T(0);
      --iu;
      iteration = 0;
    } else if (il == iu - 1) {
      schur_detail::split_off_two_rows(w, iu, exshift);
      iu -= 2;
      iteration = 0;
    } else {
      if (++total > 40 * N) return Status::schur_not_converged;
      schur_detail::francis_step(w, il, iu, iteration++, exshift);
    }
  }
  for (int e = 0; e < N * N; ++e) t[e] *= scale;
  for (int i = 0; i < N;) {
    if (i + 1 < N && t[(i + 1) * N + i] != T(0)) {
      const T p = T(0.5) * (t[i * N + i] - t[(i + 1) * N + i + 1]);
      const T b = t[i * N + i + 1], c = t[(i + 1) * N + i];
      T bound = std::abs(p) > std::abs(b) ? std::abs(p) : std::abs(b);
      bound = std::abs(c) > bound ? std::abs(c) : bound;
      const T z = bound * std::sqrt(std::abs((p / bound) * (p / bound) + (b / bound) * (c / bound)));
      w.wr[i] = w.wr[i + 1] = t[(i + 1) * N + i + 1] + p;
      w.wi[i] = z;
      w.wi[i + 1] = -z;
      i += 2;
    } else {
      w.wr[i] = t[i * N + i];
      w.wi[i] = T(0);
      ++i;
    }
  }
  return Status::ok;
}

namespace schur_detail {

// One block of the sweep with a 2×2 diagonal block on either side: T_kk'Z + Z T_ll = r by an LU
// with partial pivoting of its (bi·bj)-square matrix (core/lyapunov.cpp's solve_block).
template <class T, int N, int BI, int BJ>
void solve_block(SchurWorkspace<T, N>& w, int i0, int j0) {
  constexpr int size = BI * BJ;
  const T* t = w.t;
  T* y = w.y;
  T m[size][size], r[size];
  for (int a = 0; a < size; ++a)
    for (int b = 0; b < size; ++b) m[a][b] = T(0);
  for (int b = 0; b < BJ; ++b)
    for (int a = 0; a < BI; ++a) {
      const int row = a + BI * b;
      r[row] = reduced(w, i0 + a, j0 + b, i0, j0);
      for (int c = 0; c < BI; ++c) m[row][c + BI * b] += t[(i0 + c) * N + i0 + a];
      for (int d = 0; d < BJ; ++d) m[row][a + BI * d] += t[(j0 + d) * N + j0 + b];
    }
  for (int k = 0; k < size; ++k) {
    int pivot = k;
    for (int i = k + 1; i < size; ++i)
      if (std::abs(m[i][k]) > std::abs(m[pivot][k])) pivot = i;
    for (int c = 0; c < size; ++c) {
      const T swap = m[k][c];
      m[k][c] = m[pivot][c];
      m[pivot][c] = swap;
    }
    const T swap = r[k];
    r[k] = r[pivot];
    r[pivot] = swap;
    for (int i = k + 1; i < size; ++i) {
      const T factor = m[i][k] / m[k][k];
      for (int c = k + 1; c < size; ++c) m[i][c] -= factor * m[k][c];
      r[i] -= factor * r[k];
    }
  }
  for (int k = size - 1; k >= 0; --k) {
    for (int c = k + 1; c < size; ++c) r[k] -= m[k][c] * r[c];
    r[k] /= m[k][k];
  }
  for (int b = 0; b < BJ; ++b)
    for (int a = 0; a < BI; ++a) y[(i0 + a) * N + j0 + b] = y[(j0 + b) * N + i0 + a] = r[a + BI * b];
}

}  // namespace schur_detail

// X (row-major, exactly symmetric) with A'X + XA + Q = 0 for the A of the last real_schur() and a
// symmetric Q: Y = −U'QU, the sweep over T'Y + YT = Y for the blocks on and below the diagonal
// (core/lyapunov.cpp's LyapunovWorkspace::sweep), X = U Y U'. Status::lyapunov_singular when
// min |λi + λj| ≤ 1e-10·max(‖A‖_F, 1), as the library refuses.
template <class T, int N>
Status lyapunov_solve(SchurWorkspace<T, N>& w, const T* q, T* x) {
  T smallest = std::numeric_limits<T>::infinity();
  for (int j = 0; j < N; ++j)
    for (int i = j; i < N; ++i) {
      const T re = w.wr[i] + w.wr[j], im = w.wi[i] + w.wi[j];
      smallest = re * re + im * im < smallest ? re * re + im * im : smallest;
    }
  if (std::sqrt(smallest) <= T(1e-10) * (w.a_norm > T(1) ? w.a_norm : T(1))) return Status::lyapunov_singular;
  const T *u = w.u, *t = w.t;
  // scratch = U'Q; Y = −scratch·U on the lower half, mirrored.
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < N; ++c) {
      T sum = T(0);
      for (int k = 0; k < N; ++k) sum += u[k * N + r] * q[k * N + c];
      w.scratch[r * N + c] = sum;
    }
  for (int r = 0; r < N; ++r)
    for (int c = 0; c <= r; ++c) {
      T sum = T(0);
      for (int k = 0; k < N; ++k) sum += w.scratch[r * N + k] * u[k * N + c];
      w.y[r * N + c] = w.y[c * N + r] = -sum;
    }
  const auto block_size = [t](int i) { return i + 1 < N && t[(i + 1) * N + i] != T(0) ? 2 : 1; };
  for (int j0 = 0; j0 < N;) {
    const int bj = block_size(j0);
    for (int i0 = j0; i0 < N;) {
      const int bi = block_size(i0);
      if (bi == 1 && bj == 1) {
        w.y[i0 * N + j0] = w.y[j0 * N + i0] =
            schur_detail::reduced(w, i0, j0, i0, j0) / (t[i0 * N + i0] + t[j0 * N + j0]);
      } else if (bi == 2 && bj == 2) {
        schur_detail::solve_block<T, N, 2, 2>(w, i0, j0);
      } else if (bi == 2) {
        schur_detail::solve_block<T, N, 2, 1>(w, i0, j0);
      } else {
        schur_detail::solve_block<T, N, 1, 2>(w, i0, j0);
      }
      i0 += bi;
    }
    j0 += bj;
  }
  // X = (U Y) U' on the lower half, mirrored.
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < N; ++c) {
      T sum = T(0);
      for (int k = 0; k < N; ++k) sum += u[r * N + k] * w.y[k * N + c];
      w.scratch[r * N + c] = sum;
    }
  for (int r = 0; r < N; ++r)
    for (int c = 0; c <= r; ++c) {
      T sum = T(0);
      for (int k = 0; k < N; ++k) sum += w.scratch[r * N + k] * u[c * N + k];
      x[r * N + c] = x[c * N + r] = sum;
    }
  for (int e = 0; e < N * N; ++e)
    if (!std::isfinite(x[e])) return Status::not_finite;
  return Status::ok;
}

}  // namespace thetad_onboard

#endif  // THETAD_ONBOARD_LYAPUNOV_SCHUR
