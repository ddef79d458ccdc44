#pragma once
// Checks on covariance matrices read from files (graph.tsv edges): a covariance used as a
// weight (its inverse) must be finite, symmetric and positive definite.

#include "core/geometry/se2.h"

namespace atlas {

// True when `cov` is finite, symmetric (to rounding) and positive definite: every pivot of its
// LDL^T factorisation is above 1e-14 times its largest diagonal entry, so its inverse exists
// and is itself a covariance. A singular matrix (all entries 1) or a zero or negative variance
// is not.
bool IsPositiveDefiniteCovariance(const Mat3& cov);

}  // namespace atlas
