#pragma once

// SLICOT routines called by the benchmarks. Debian's libslicot-dev ships no header, so the
// Fortran interfaces are declared here by hand. gfortran conventions: lower-case name with a
// trailing underscore, every argument by pointer, LOGICAL as int, arrays column-major, and one
// hidden length (size_t) per CHARACTER argument appended after the declared arguments.

#include <cstddef>

extern "C" {

// SB02MD (SLICOT 5.x): Laub's Schur method for Q + A'X + XA − XGX = 0 (DICO = 'C').
// G and Q: only the UPLO triangle is read. Q is overwritten with X; A is unchanged for 'C'.
// Workspace: IWORK and BWORK 2N, DWORK LDWORK ≥ max(2, 6N); S and U are 2N×2N outputs.
// INFO: 0 ok; 2 Schur form failed; 3 reordering failed; 4 fewer than N stable eigenvalues;
// 5 the system for X is singular to working precision.
void sb02md_(const char* dico, const char* hinv, const char* uplo, const char* scal,
             const char* sort, const int* n, double* a, const int* lda, double* g, const int* ldg,
             double* q, const int* ldq, double* rcond, double* wr, double* wi, double* s,
             const int* lds, double* u, const int* ldu, int* iwork, double* dwork,
             const int* ldwork, int* bwork, int* info, std::size_t dico_len, std::size_t hinv_len,
             std::size_t uplo_len, std::size_t scal_len, std::size_t sort_len);
}

#include <string>
#include <vector>

#include <Eigen/Dense>

namespace thetad::bench {

// SB02MD for Q + A'X + XA − XGX = 0 with its workspace allocated once (a generous LDWORK, not
// the minimum 6N, so that DGEES may block): general scaling (SCAL = 'G'), stable eigenvalues
// first, the upper triangles of G and Q read.
class Sb02md {
 public:
  explicit Sb02md(int n)
      : n_(n), ldwork_(6 * n + 128 * n), a_(n, n), s_(2 * n, 2 * n), u_(2 * n, 2 * n), wr_(2 * n), wi_(2 * n),
        dwork_(ldwork_), iwork_(2 * n), bwork_(2 * n) {}

  // X on entry is overwritten; returns SB02MD's INFO (0: solved).
  int solve(const Eigen::MatrixXd& A, Eigen::MatrixXd& G, const Eigen::MatrixXd& Q, Eigen::MatrixXd& X) {
    const int n2 = 2 * n_;
    a_ = A;
    X = Q;
    int info = 0;
    sb02md_("C", "D", "U", "G", "S", &n_, a_.data(), &n_, G.data(), &n_, X.data(), &n_, &rcond_, wr_.data(),
            wi_.data(), s_.data(), &n2, u_.data(), &n2, iwork_.data(), dwork_.data(), &ldwork_, bwork_.data(), &info,
            1, 1, 1, 1, 1);
    return info;
  }
  double rcond() const { return rcond_; }

 private:
  int n_;
  int ldwork_;
  Eigen::MatrixXd a_, s_, u_;
  Eigen::VectorXd wr_, wi_, dwork_;
  std::vector<int> iwork_, bwork_;
  double rcond_ = 0.0;
};

}  // namespace thetad::bench
