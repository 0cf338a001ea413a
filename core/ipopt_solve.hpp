#pragma once

#include <string>

namespace Ipopt {
class TNLP;
}

namespace thetad {

// How Ipopt is run on one of thetad's NLPs (the trim, the optimal control transcription).
struct IpoptRun {
  int max_iterations = 200;       // max_iter
  double tolerance = 1e-8;        // tol
  double constraint_tolerance = 1e-8;  // constr_viol_tol
  double max_seconds = 1e6;       // max_cpu_time
  int lbfgs_history = 6;          // limited_memory_max_history: pairs the L-BFGS Hessian keeps
  // nlp_scaling_method: the TNLP's get_scaling_parameters instead of Ipopt's gradient-based scaling.
  bool user_scaling = false;
};

// What Ipopt said at the end of a solve.
struct IpoptOutcome {
  std::string status;      // the ApplicationReturnStatus name ("Solve_Succeeded", ...)
  bool converged = false;  // Solve_Succeeded or Solved_To_Acceptable_Level
};

// Solves `nlp` with Ipopt: MUMPS (the only linear solver Debian's Ipopt has), a limited-memory
// (L-BFGS) Hessian, no output, no ipopt.opt read from the working directory. Solves are
// serialized over the whole process: Ipopt with MUMPS keeps global state and is not thread-safe.
// `nlp` must be held by an Ipopt::SmartPtr of the caller's (Ipopt shares its ownership).
IpoptOutcome solve_with_ipopt(Ipopt::TNLP& nlp, const IpoptRun& run);

}  // namespace thetad
