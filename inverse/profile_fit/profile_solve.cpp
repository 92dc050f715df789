#include "inverse/profile_fit/profile_solve.hpp"

#include <algorithm>
#include <cmath>

#include <nlopt.hpp>

#include "spectral/input_error.hpp"
#include "spectral/text_fields.hpp"

namespace skinspec {

ProfileEstimate solve_profile(const ProfileSystem& system, const ProfileSolveOptions& options) {
    if (!(options.tikhonov_lambda >= 0.0 && std::isfinite(options.tikhonov_lambda))) {
        throw InputError("Tikhonov lambda = " + format_number(options.tikhonov_lambda) + " is outside [0, inf)");
    }
    const auto& w = system.w;
    const Eigen::Index n = w.cols();
    Eigen::VectorXd r;
    long rank = 0;
    if (options.tikhonov_lambda > 0.0) {
        // [W; lambda I] r = [l; 0]
        Eigen::MatrixXd a(w.rows() + n, n);
        a << w, options.tikhonov_lambda * Eigen::MatrixXd::Identity(n, n);
        Eigen::VectorXd b(w.rows() + n);
        b << system.l, Eigen::VectorXd::Zero(n);
        const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(a);
        r = cod.solve(b);
        rank = cod.rank();
    } else {
        const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(w);
        r = cod.solve(system.l);  // the minimum-norm least-squares solution: W^+ l
        rank = cod.rank();
    }
    if (options.non_negative) {
        // min |W r - l|^2 (+ lambda^2 |r|^2) with r >= 0, via the normal equations' quadratic form.
        const Eigen::MatrixXd normal = w.transpose() * w + options.tikhonov_lambda * options.tikhonov_lambda * Eigen::MatrixXd::Identity(n, n);
        const Eigen::VectorXd rhs = w.transpose() * system.l;
        const double scale = std::max(1e-300, system.l.squaredNorm());
        nlopt::opt opt(nlopt::LD_LBFGS, static_cast<unsigned>(n));
        opt.set_lower_bounds(0.0);
        opt.set_ftol_rel(1e-14);
        opt.set_maxeval(20000);
        struct Data {
            const Eigen::MatrixXd* normal;
            const Eigen::VectorXd* rhs;
            double scale;
        } data{&normal, &rhs, scale};
        opt.set_min_objective(
            [](const std::vector<double>& x, std::vector<double>& grad, void* p) {
                const auto& d = *static_cast<Data*>(p);
                const Eigen::Map<const Eigen::VectorXd> v(x.data(), static_cast<Eigen::Index>(x.size()));
                const Eigen::VectorXd nv = *d.normal * v;
                if (!grad.empty()) Eigen::Map<Eigen::VectorXd>(grad.data(), static_cast<Eigen::Index>(grad.size())) = 2.0 * (nv - *d.rhs) / d.scale;
                return (v.dot(nv) - 2.0 * v.dot(*d.rhs)) / d.scale;
            },
            &data);
        std::vector<double> x(static_cast<std::size_t>(n));
        for (Eigen::Index i = 0; i < n; ++i) x[static_cast<std::size_t>(i)] = std::max(0.0, r[i]);
        double value = 0.0;
        try {
            opt.optimize(x, value);
        } catch (const nlopt::roundoff_limited&) {
            // converged as far as rounding allows
        }
        r = Eigen::Map<const Eigen::VectorXd>(x.data(), n);
    }
    ProfileEstimate out;
    out.rank = rank;
    out.residual_norm = (w * r - system.l).norm();
    out.has_data = system.bin_has_data;
    for (Eigen::Index i = 0; i < n; ++i) {
        out.distances_mm.push_back(system.bin_distance_mm(static_cast<std::size_t>(i)));
        out.profile_per_mm2.push_back(r[i]);
    }
    return out;
}

}  // namespace skinspec
