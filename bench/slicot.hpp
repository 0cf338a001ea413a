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

// SB02OD (SLICOT 5.x): the method of deflating subspaces (van Dooren 1981) for
// Q + A'X + XA − (L + XB)R⁻¹(L + XB)' = 0 (DICO = 'C'): QZ on the extended (2N+M) pencil built
// from B and R themselves, so R⁻¹ and G are never formed. Q and R: only the UPLO triangle is read;
// A, B, Q, R are not changed. S and T are (2N+M)×(2N+M) and (2N+M)×2N outputs, U 2N×2N.
// Workspace: IWORK max(1, M, 2N), DWORK LDWORK ≥ max(7(2N+1)+16, 16N, 2N+M, 3M), BWORK 2N.
// INFO: 0 ok; 1 the extended pencil is singular; 2 QZ failed; 3 reordering failed; 4 rounding
// moved eigenvalues across the axis after reordering; 5 not N stable eigenvalues; 6 the system
// for X is singular.
void sb02od_(const char* dico, const char* jobb, const char* fact, const char* uplo, const char* jobl,
             const char* sort, const int* n, const int* m, const int* p, const double* a, const int* lda,
             const double* b, const int* ldb, const double* q, const int* ldq, const double* r, const int* ldr,
             const double* l, const int* ldl, double* rcond, double* x, const int* ldx, double* alfar,
             double* alfai, double* beta, double* s, const int* lds, double* t, const int* ldt, double* u,
             const int* ldu, const double* tol, int* iwork, double* dwork, const int* ldwork, int* bwork,
             int* info, std::size_t dico_len, std::size_t jobb_len, std::size_t fact_len, std::size_t uplo_len,
             std::size_t jobl_len, std::size_t sort_len);
}

#include <algorithm>
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

// SB02OD for Q + A'X + XA − XBR⁻¹B'X = 0 from B and R (JOBB = 'B', FACT = 'N', no cross term
// L), stable eigenvalues first, the upper triangles of Q and R read, the default tolerance (eps)
// for the pencil's compression; workspace allocated once, generous as for SB02MD.
class Sb02od {
 public:
  Sb02od(int n, int m)
      : n_(n), m_(m), ldwork_(std::max({7 * (2 * n + 1) + 16, 16 * n, 2 * n + m, 3 * m}) + 128 * (2 * n + m)),
        s_(2 * n + m, 2 * n + m), t_(2 * n + m, 2 * n), u_(2 * n, 2 * n), alfar_(2 * n), alfai_(2 * n),
        beta_(2 * n), dwork_(ldwork_), iwork_(std::max({1, m, 2 * n})), bwork_(2 * n) {}

  // X is resized and overwritten; returns SB02OD's INFO (0: solved).
  int solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R,
            Eigen::MatrixXd& X) {
    const int lds = 2 * n_ + m_;
    const int ldu = 2 * n_;
    const int p = 0;  // rows of C and D: FACT = 'N' reads Q and R instead
    const int ldl = 1;
    const double l = 0.0;
    const double tol = 0.0;
    X.resize(n_, n_);
    int info = 0;
    sb02od_("C", "B", "N", "U", "Z", "S", &n_, &m_, &p, A.data(), &n_, B.data(), &n_, Q.data(), &n_, R.data(), &m_,
            &l, &ldl, &rcond_, X.data(), &n_, alfar_.data(), alfai_.data(), beta_.data(), s_.data(), &lds,
            t_.data(), &lds, u_.data(), &ldu, &tol, iwork_.data(), dwork_.data(), &ldwork_, bwork_.data(), &info, 1,
            1, 1, 1, 1, 1);
    return info;
  }

 private:
  int n_, m_;
  int ldwork_;
  Eigen::MatrixXd s_, t_, u_;
  Eigen::VectorXd alfar_, alfai_, beta_, dwork_;
  std::vector<int> iwork_, bwork_;
  double rcond_ = 0.0;
};

}  // namespace thetad::bench
