// bench_ellint_boost.cpp — C shim over Boost.Math ellint_1 / ellint_2 for bench_ellint.c.
// NOTE: Boost takes the MODULUS k (m = k^2), not the parameter m. Default policy except that
// overflow (k rounded to 1 when m1 < 1.1e-16, K = inf) returns inf instead of throwing.
#define BOOST_MATH_OVERFLOW_ERROR_POLICY ignore_error
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>

extern "C" double ics_bench_boost_ellint_1(double k) { return boost::math::ellint_1(k); }
extern "C" double ics_bench_boost_ellint_2(double k) { return boost::math::ellint_2(k); }
