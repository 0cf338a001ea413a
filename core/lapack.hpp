#pragma once

// LAPACK through LAPACKE's C interface. Complex arguments are std::complex<double>.
#include <complex>
#define lapack_complex_float std::complex<float>
#define lapack_complex_double std::complex<double>
#include <lapacke.h>
