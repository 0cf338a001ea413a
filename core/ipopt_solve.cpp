#include "core/ipopt_solve.hpp"

#include <mutex>

#include "IpIpoptApplication.hpp"
#include "IpTNLP.hpp"

namespace thetad {

namespace {

const char* status_name(Ipopt::ApplicationReturnStatus status) {
  switch (status) {
    case Ipopt::Solve_Succeeded: return "Solve_Succeeded";
    case Ipopt::Solved_To_Acceptable_Level: return "Solved_To_Acceptable_Level";
    case Ipopt::Infeasible_Problem_Detected: return "Infeasible_Problem_Detected";
    case Ipopt::Search_Direction_Becomes_Too_Small: return "Search_Direction_Becomes_Too_Small";
    case Ipopt::Diverging_Iterates: return "Diverging_Iterates";
    case Ipopt::User_Requested_Stop: return "User_Requested_Stop";
    case Ipopt::Feasible_Point_Found: return "Feasible_Point_Found";
    case Ipopt::Maximum_Iterations_Exceeded: return "Maximum_Iterations_Exceeded";
    case Ipopt::Restoration_Failed: return "Restoration_Failed";
    case Ipopt::Error_In_Step_Computation: return "Error_In_Step_Computation";
    case Ipopt::Maximum_CpuTime_Exceeded: return "Maximum_CpuTime_Exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom: return "Not_Enough_Degrees_Of_Freedom";
    case Ipopt::Invalid_Problem_Definition: return "Invalid_Problem_Definition";
    case Ipopt::Invalid_Option: return "Invalid_Option";
    case Ipopt::Invalid_Number_Detected: return "Invalid_Number_Detected";
    case Ipopt::Unrecoverable_Exception: return "Unrecoverable_Exception";
    case Ipopt::NonIpopt_Exception_Thrown: return "NonIpopt_Exception_Thrown";
    case Ipopt::Insufficient_Memory: return "Insufficient_Memory";
    case Ipopt::Internal_Error: return "Internal_Error";
  }
  return "unknown Ipopt status";
}

std::mutex ipopt_mutex;

}  // namespace

IpoptOutcome solve_with_ipopt(Ipopt::TNLP& nlp, const IpoptRun& run) {
  const Ipopt::SmartPtr<Ipopt::TNLP> shared(&nlp);
  Ipopt::ApplicationReturnStatus status;
  {
    const std::lock_guard<std::mutex> lock(ipopt_mutex);
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
    auto& options = *app->Options();
    options.SetIntegerValue("print_level", 0);
    options.SetStringValue("sb", "yes");
    options.SetStringValue("linear_solver", "mumps");
    options.SetStringValue("hessian_approximation", "limited-memory");
    options.SetIntegerValue("max_iter", run.max_iterations);
    options.SetNumericValue("tol", run.tolerance);
    options.SetNumericValue("constr_viol_tol", run.constraint_tolerance);
    options.SetNumericValue("max_cpu_time", run.max_seconds);
    options.SetIntegerValue("limited_memory_max_history", run.lbfgs_history);
    if (run.user_scaling) options.SetStringValue("nlp_scaling_method", "user-scaling");
    status = app->Initialize("");  // "": no ipopt.opt from the working directory
    if (status == Ipopt::Solve_Succeeded) status = app->OptimizeTNLP(shared);
  }
  return {status_name(status), status == Ipopt::Solve_Succeeded || status == Ipopt::Solved_To_Acceptable_Level};
}

}  // namespace thetad
