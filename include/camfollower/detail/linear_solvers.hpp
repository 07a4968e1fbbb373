// SPDX-License-Identifier: BSD-3-Clause
// The decompositions the motion laws' construction needs (a spline's collocation system, a polynomial
// lift's conditions, a least-squares harmonic fit) as function templates: instantiated only in a unit
// that calls them, and compiled in camfollower::precompiled for the units that link it
// (detail/precompiled_use.hpp), where naming them in the laws' inline code would otherwise cost every
// including unit the seconds that instantiating Eigen's SparseLU, QR and SVD takes.
#pragma once

#include <limits>

#include <Eigen/Core>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "camfollower/detail/precompiled_use.hpp"

namespace camfollower::detail {

template <class Scalar>
using DynamicVector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
template <class Scalar>
using DynamicMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

// x = a^-1 b by sparse LU; false when a is singular or x not finite.
template <class Scalar>
bool sparse_lu_solve(const Eigen::SparseMatrix<Scalar>& a, const DynamicVector<Scalar>& b, DynamicVector<Scalar>& x) {
    Eigen::SparseLU<Eigen::SparseMatrix<Scalar>> lu;
    lu.compute(a);
    if (lu.info() != Eigen::Success) return false;
    x = lu.solve(b);
    return x.allFinite();
}

// The least-squares solution x of a x = b by column-pivoting QR, pivots below threshold (relative)
// taken as zero; returns the numerical rank (x is meaningful when it equals a's column count).
template <class Scalar>
Eigen::Index qr_least_squares(const DynamicMatrix<Scalar>& a, const DynamicVector<Scalar>& b, double threshold,
                              DynamicVector<Scalar>& x) {
    Eigen::ColPivHouseholderQR<DynamicMatrix<Scalar>> qr(a);
    qr.setThreshold(threshold);
    x = qr.solve(b);
    return qr.rank();
}

// x = a^-1 b for a square a by SVD; returns a's 2-norm condition number (infinite when singular).
template <class Scalar>
Scalar svd_solve(const DynamicMatrix<Scalar>& a, const DynamicVector<Scalar>& b, DynamicVector<Scalar>& x) {
    const Eigen::JacobiSVD<DynamicMatrix<Scalar>> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const auto& s = svd.singularValues();
    x = svd.solve(b);
    const Eigen::Index last = s.size() - 1;
    return s(last) > Scalar(0) ? s(0) / s(last) : std::numeric_limits<Scalar>::infinity();
}

}  // namespace camfollower::detail

// CAMFOLLOWER_LINEAR_SOLVER_INSTANCES(extern) declares the instantiations; (): defines them (in
// camfollower::precompiled only).
#define CAMFOLLOWER_LINEAR_SOLVER_INSTANCES(PREFIX)                                                               \
    PREFIX template bool camfollower::detail::sparse_lu_solve<double>(const Eigen::SparseMatrix<double>&,         \
                                                                      const Eigen::VectorXd&, Eigen::VectorXd&);  \
    PREFIX template Eigen::Index camfollower::detail::qr_least_squares<double>(                                   \
        const Eigen::MatrixXd&, const Eigen::VectorXd&, double, Eigen::VectorXd&);                                \
    PREFIX template double camfollower::detail::svd_solve<double>(const Eigen::MatrixXd&, const Eigen::VectorXd&, \
                                                                  Eigen::VectorXd&);

#if CAMFOLLOWER_USE_PRECOMPILED
CAMFOLLOWER_LINEAR_SOLVER_INSTANCES(extern)
#endif
