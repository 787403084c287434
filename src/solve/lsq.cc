// Ceres adapter behind the extern "C" API of lsq.h.
//
// Why C++ here at all: Ceres' own C API (ceres_solve) takes no options and
// prints a full report on stdout on every call.  This file keeps Ceres'
// C++ surface out of the rest of dflab: no exception and no log line may
// cross the extern "C" boundary.

// lsq.h includes core/status.h, which carries its own extern "C" guard, so
// the C API keeps C linkage here without a wrapper.
#include "solve/lsq.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <cmath>
#include <exception>
#include <mutex>
#include <new>
#include <algorithm>
#include <vector>

struct dfl_lsq_ctx {
    ceres::Context *context;
};

namespace {

const int kMaxParams = 16;
const int kMaxResiduals = 64;

// One residual block over one parameter block of size n; forwards to the C
// callback, which fills a row-major m x n Jacobian, exactly the layout Ceres
// wants for a single parameter block.
class CallbackCost : public ceres::CostFunction {
  public:
    CallbackCost(int n, int m, dfl_lsq_residual_fn fn, void *user) : fn_(fn), user_(user)
    {
        set_num_residuals(m);
        mutable_parameter_block_sizes()->push_back(n);
    }

    bool Evaluate(double const *const *parameters, double *residuals,
                  double **jacobians) const override
    {
        double *J = (jacobians && jacobians[0]) ? jacobians[0] : nullptr;
        return fn_(user_, parameters[0], residuals, J) == 0;
    }

  private:
    dfl_lsq_residual_fn fn_;
    void *user_;
};

// glog's flag is process-global; set it once, before any solve can log.
std::once_flag g_glog_once;

void quiet_glog()
{
    FLAGS_minloglevel = google::GLOG_FATAL;
    FLAGS_logtostderr = false;
    FLAGS_stderrthreshold = google::GLOG_FATAL;
}

// The status of the exception being handled; call it only from a catch
// block (it rethrows to tell the kinds apart).  step names what was being
// done, for the message.  This is where every exception stops: none may
// cross the extern "C" boundary.
dfl_status caught(const char *step, dfl_err *err)
{
    try {
        throw;
    } catch (const std::bad_alloc &) {
        return dfl_err_set(err, DFL_E_NOMEM, "lsq: out of memory %s", step);
    } catch (const std::exception &e) {
        return dfl_err_set(err, DFL_E_INTERNAL, "lsq: %s: %.300s", step, e.what());
    } catch (...) {
        return dfl_err_set(err, DFL_E_INTERNAL, "lsq: unknown exception %s", step);
    }
}

}  // namespace

extern "C" {

void dfl_lsq_options_default(dfl_lsq_options *opt)
{
    opt->max_iterations = 100;
    opt->function_tolerance = 1e-16;
    opt->gradient_tolerance = 1e-16;
    opt->parameter_tolerance = 1e-14;
}

dfl_status dfl_lsq_ctx_new(dfl_lsq_ctx **out, dfl_err *err)
{
    try {
        std::call_once(g_glog_once, quiet_glog);
        dfl_lsq_ctx *c = new dfl_lsq_ctx;
        c->context = ceres::Context::Create();
        *out = c;
        return DFL_OK;
    } catch (...) {
        return caught("creating the Ceres context", err);
    }
}

void dfl_lsq_ctx_free(dfl_lsq_ctx *ctx)
{
    if (!ctx) return;
    try {
        delete ctx->context;
        delete ctx;
    } catch (...) {
        // nothing sensible to report from a destructor path
    }
}

dfl_status dfl_lsq_solve(dfl_lsq_ctx *ctx, int n, int m, dfl_lsq_residual_fn fn, void *user,
                         const double *lo, const double *hi, const dfl_lsq_options *opt,
                         double *x, dfl_lsq_result *res, dfl_err *err)
{
    if (!ctx || !fn || !x)
        return dfl_err_set(err, DFL_E_INTERNAL, "lsq: NULL context, callback or x");
    if (n < 1 || n > kMaxParams || m < 1 || m > kMaxResiduals)
        return dfl_err_set(err, DFL_E_INPUT, "lsq: sizes n = %d (1..%d), m = %d (1..%d)", n,
                           kMaxParams, m, kMaxResiduals);
    dfl_lsq_options o;
    if (opt)
        o = *opt;
    else
        dfl_lsq_options_default(&o);
    for (int j = 0; j < n; j++) {
        double l = lo ? lo[j] : -HUGE_VAL, h = hi ? hi[j] : HUGE_VAL;
        if (!(l <= h))
            return dfl_err_set(err, DFL_E_INPUT, "lsq: bound %d empty: [%g, %g]", j, l, h);
        if (!(x[j] >= l && x[j] <= h))
            return dfl_err_set(err, DFL_E_INPUT, "lsq: start x[%d] = %g outside [%g, %g]", j,
                               x[j], l, h);
    }
    // Coordinates with lo == hi are held (Ceres refuses an upper bound equal
    // to the lower one as infeasible): fixed in every round, never bounded.
    std::vector<int> pinned;
    for (int j = 0; j < n; j++)
        if (lo && hi && lo[j] == hi[j]) pinned.push_back(j);
    if ((int)pinned.size() == n) {
        double r[kMaxResiduals];
        if (fn(user, x, r, nullptr) != 0)
            return dfl_err_set(err, DFL_E_NUMERIC, "lsq: the residual failed at the start");
        if (res) {
            double c = 0.0;
            for (int i = 0; i < m; i++) c += r[i] * r[i];
            res->final_cost = 0.5 * c;
            res->iterations = 0;
            res->converged = 1;
        }
        return DFL_OK;
    }
    auto is_pinned = [&](int j) {
        return std::find(pinned.begin(), pinned.end(), j) != pinned.end();
    };
    try {
        ceres::Solver::Options so;
        so.minimizer_type = ceres::TRUST_REGION;
        so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
        so.linear_solver_type = ceres::DENSE_QR;
        so.logging_type = ceres::SILENT;
        so.minimizer_progress_to_stdout = false;
        so.max_num_iterations = o.max_iterations;
        so.function_tolerance = o.function_tolerance;
        so.gradient_tolerance = o.gradient_tolerance;
        so.parameter_tolerance = o.parameter_tolerance;
        so.num_threads = 1;
        ceres::Solver::Summary summary;
        std::vector<int> fixed = pinned;
        int total_iter = 0;
        bool converged = true;
        // Round 0 solves with the box.  Ceres projects its steps onto the box,
        // and LM stalls there when the step mostly points out of the box: it
        // stops with "parameter tolerance" while the free coordinates are
        // still off their constrained optimum (a 2-parameter fit with one
        // active bound ends 3% high in cost).  Later rounds fix the active
        // coordinates (SubsetManifold), release those whose gradient sign
        // violates the KKT conditions, and re-solve the free ones.
        for (int round = 0; round < 2 * n + 2; round++) {
            CallbackCost cost(n, m, fn, user);
            ceres::Problem::Options popt;
            popt.context = ctx->context;
            popt.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
            popt.manifold_ownership = ceres::TAKE_OWNERSHIP;
            ceres::Problem problem(popt);
            problem.AddResidualBlock(&cost, nullptr, x);
            if (!fixed.empty()) problem.SetManifold(x, new ceres::SubsetManifold(n, fixed));
            for (int j = 0; j < n; j++) {
                if (is_pinned(j)) continue;
                if (lo && std::isfinite(lo[j])) problem.SetParameterLowerBound(x, j, lo[j]);
                if (hi && std::isfinite(hi[j])) problem.SetParameterUpperBound(x, j, hi[j]);
            }
            ceres::Solve(so, &problem, &summary);
            total_iter += (int)summary.iterations.size();
            if (summary.termination_type == ceres::FAILURE)
                return dfl_err_set(err, DFL_E_NUMERIC, "lsq: Ceres failed: %.300s",
                                   summary.message.c_str());
            converged = summary.termination_type == ceres::CONVERGENCE;
            if (!lo && !hi) break;
            // KKT check at x: gradient of the cost, g = J^T r
            double r[kMaxResiduals], J[kMaxResiduals * kMaxParams], g[kMaxParams];
            if (fn(user, x, r, J) != 0) break;
            for (int j = 0; j < n; j++) {
                g[j] = 0.0;
                for (int i = 0; i < m; i++) g[j] += J[i * n + j] * r[i];
            }
            std::vector<int> next;
            for (int j = 0; j < n; j++) {
                bool at_lo = lo && x[j] <= lo[j], at_hi = hi && x[j] >= hi[j];
                // held, or active and pushing outwards: keep it fixed
                if (is_pinned(j) || (at_lo && g[j] >= 0.0) || (at_hi && g[j] <= 0.0))
                    next.push_back(j);
            }
            if ((int)next.size() == n || next == fixed) break;
            fixed = next;
        }
        if (res) {
            res->final_cost = summary.final_cost;
            res->iterations = total_iter;
            res->converged = converged;
        }
        return DFL_OK;
    } catch (...) {
        return caught("while solving", err);
    }
}

}  // extern "C"
