#pragma once
// The standard normal's quantile function (inverse CDF): P. J. Acklam's rational
// approximation refined by one Newton step on the CDF, |error| < 1e-12 in practice. p is
// clamped to (0, 1). Used for gates (chi-square quantiles via Wilson-Hilferty) and for the
// simulator's noise table.

namespace atlas {

double NormalQuantile(double p);

}  // namespace atlas
