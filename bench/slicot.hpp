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
