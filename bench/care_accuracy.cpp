// Forward error of the CARE solvers against 40-digit reference solutions: thetad's automatic,
// matrix-sign and Schur methods and SLICOT SB02MD and SB02OD, on the paper's problem and on random
// problems: with the paper's weight spread at n = 12, 18 (the first is riccati_bench's n18_m5) and
// 36, the same in badly scaled state coordinates at n = 10 and 18, and with Q = I, R = I.
//
//   care_accuracy write DIR [COUNT]        the problems, DIR/NAME.txt (COUNT random n = 18 ones,
//                                          default 12, and up to 4 of each other family)
//   care_accuracy write-ill-r DIR [COUNT]  instead: n = 6, m = 3 problems with κ(R) in 1e7 … 1e10
//                                          (as CAREX 2.2), default 16
//   /usr/bin/python3 scripts/care_reference.py DIR    their reference solutions, DIR/NAME.ref
//   care_accuracy compare DIR               the table in docs/riccati.md
//
// The residual alone cannot rank solvers on these problems: the exact solution rounded to double
// precision already has a relative residual of 1e-10 … 1e-7 (the column "rounded"), because the
// terms of the equation are 1e7 times larger than Q and cancel.

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bench/care_problems.hpp"
#include "bench/slicot.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/riccati.hpp"

namespace {

using Eigen::MatrixXd;
namespace fs = std::filesystem;
using thetad::bench::CareProblem;

std::string matrix_block(const char* name, const MatrixXd& M) {
  std::ostringstream out;
  out << name << ' ' << M.rows() << ' ' << M.cols() << '\n';
  char number[32];
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    for (Eigen::Index j = 0; j < M.cols(); ++j) {
      std::snprintf(number, sizeof number, "%.17g", M(i, j));
      out << (j ? " " : "") << number;
    }
    out << '\n';
  }
  return out.str();
}

// Blocks "NAME ROWS COLS" followed by ROWS lines of COLS numbers; '#' lines are comments.
std::map<std::string, MatrixXd> read_matrices(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw thetad::Error(path.string() + ": cannot open");
  std::map<std::string, MatrixXd> matrices;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream header(line);
    std::string name;
    Eigen::Index rows = 0, cols = 0;
    if (!(header >> name >> rows >> cols) || rows <= 0 || cols <= 0)
      throw thetad::Error(path.string() + ": expected 'NAME ROWS COLS', got '" + line + "'");
    MatrixXd M(rows, cols);
    for (Eigen::Index i = 0; i < rows; ++i)
      for (Eigen::Index j = 0; j < cols; ++j) {
        std::string value;  // strtod: the references carry 25 digits
        if (!(in >> value)) throw thetad::Error(path.string() + ": matrix " + name + " is cut short");
        M(i, j) = std::strtod(value.c_str(), nullptr);
      }
    matrices[name] = M;
  }
  return matrices;
}

const MatrixXd& field(const std::map<std::string, MatrixXd>& matrices, const std::string& name, const fs::path& path) {
  const auto it = matrices.find(name);
  if (it == matrices.end()) throw thetad::Error(path.string() + ": no matrix " + name);
  return it->second;
}

using ProblemMaker = CareProblem (*)(std::string, Eigen::Index, Eigen::Index, std::mt19937_64&);

// COUNT problems NAME_k of one family, seeded seed + 7919k.
void add_family(std::vector<CareProblem>& problems, const std::string& name, ProblemMaker make, Eigen::Index n,
                Eigen::Index m, std::uint64_t seed, int count) {
  for (int k = 0; k < count; ++k) {
    std::mt19937_64 rng(seed + 7919 * static_cast<std::uint64_t>(k));
    problems.push_back(make(name + "_" + std::to_string(k), n, m, rng));
  }
}

std::vector<CareProblem> study_problems(int count) {
  using namespace thetad::bench;
  std::vector<CareProblem> problems{paper_care_problem()};
  const int others = std::min(count, 4);
  // Seed 1000n + m for the first of a family, as riccati_bench's n18_m5.
  add_family(problems, "n18_m5", random_care_problem, 18, 5, 18005, count);
  add_family(problems, "n12_m4", random_care_problem, 12, 4, 12004, others);
  add_family(problems, "n36_m10", random_care_problem, 36, 10, 36010, others);
  add_family(problems, "scaled_n10_m3", diagonally_scaled_care_problem, 10, 3, 10003, others);
  add_family(problems, "scaled_n18_m5", diagonally_scaled_care_problem, 18, 5, 18005, std::min(count, 2));
  add_family(problems, "unit_n18_m6", unit_weight_care_problem, 18, 6, 18006, std::min(count, 2));
  add_family(problems, "unit_n40_m13", unit_weight_care_problem, 40, 13, 40013, std::min(count, 1));
  return problems;
}

std::vector<CareProblem> ill_conditioned_r_problems(int count) {
  std::vector<CareProblem> problems;
  for (int k = 0; k < count; ++k) {
    std::mt19937_64 rng(6003 + 7919 * static_cast<std::uint64_t>(k));
    problems.push_back(thetad::bench::ill_conditioned_r_problem("ill_r_" + std::to_string(k), 6, 3, 7.0, 10.0, rng));
  }
  return problems;
}

void write(const fs::path& dir, const std::vector<CareProblem>& problems) {
  for (const CareProblem& p : problems)
    thetad::write_file_atomically(dir / (p.name + ".txt"), "# " + p.name + ", written by care_accuracy\n" +
                                                               matrix_block("A", p.A) + matrix_block("B", p.B) +
                                                               matrix_block("Q", p.Q) + matrix_block("R", p.R));
  std::printf("%zu problems in %s\n", problems.size(), dir.c_str());
}

void compare(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".txt") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw thetad::Error(dir.string() + ": no problems (run care_accuracy write first)");

  std::printf("relative forward error ‖P − P_ref‖_F/‖P_ref‖_F; the error and condition estimates of automatic "
              "(ErrorEstimates::on); relative residual ‖Res‖_F/max(1, ‖Q‖_F)\n");
  std::printf("%-16s | %-9s %-9s %-9s %-9s %-9s | %-9s %-9s | %-9s %-9s %-9s %-9s %-9s %-9s | %s\n", "problem",
              "automatic", "sign", "schur", "SB02MD", "SB02OD", "estimate", "condition", "automatic", "sign", "schur",
              "SB02MD", "SB02OD", "rounded", "sign it.");
  for (const fs::path& path : files) {
    const auto problem = read_matrices(path);
    fs::path ref_path = path;
    ref_path.replace_extension(".ref");
    const CareProblem p{path.stem().string(), field(problem, "A", path), field(problem, "B", path),
                        field(problem, "Q", path), field(problem, "R", path)};
    const auto& [name, A, B, Q, R] = p;
    const MatrixXd P_ref = field(read_matrices(ref_path), "P", ref_path);
    const auto forward = [&](const MatrixXd& P) { return (P - P_ref).norm() / P_ref.norm(); };
    const auto residual = [&](const MatrixXd& P) { return thetad::bench::relative_residual(p, P); };
    // A method that refuses the equation (matrix_sign near the imaginary axis) shows "refused".
    std::vector<std::optional<MatrixXd>> solutions;
    int sign_iterations = 0;
    double estimate = 0.0;
    double condition = 0.0;
    for (const auto method : {thetad::CareMethod::automatic, thetad::CareMethod::matrix_sign, thetad::CareMethod::schur}) {
      try {
        const thetad::CareResult result = thetad::solve_care(A, B, Q, R, method, thetad::ErrorEstimates::on);
        if (method == thetad::CareMethod::automatic) {
          sign_iterations = result.sign_iterations;
          estimate = result.forward_error;
          condition = result.condition;
        }
        solutions.emplace_back(result.P);
      } catch (const thetad::Error&) {
        solutions.emplace_back();
      }
    }
    thetad::bench::Sb02md sb02md(static_cast<int>(A.rows()));
    MatrixXd G = B * R.llt().solve(B.transpose());  // SB02MD scales it in place
    MatrixXd slicot;
    const int info = sb02md.solve(A, G, Q, slicot);
    solutions.push_back(info == 0 ? std::optional<MatrixXd>(slicot) : std::nullopt);
    thetad::bench::Sb02od sb02od(static_cast<int>(A.rows()), static_cast<int>(B.cols()));
    const int od_info = sb02od.solve(A, B, Q, R, slicot);
    solutions.push_back(od_info == 0 ? std::optional<MatrixXd>(slicot) : std::nullopt);

    const auto cells = [&](const auto& measure) {
      std::string text;
      char cell[16];
      for (const auto& P : solutions) {
        std::snprintf(cell, sizeof cell, "%-9.1e ", P ? measure(*P) : 0.0);
        text += P ? cell : "refused   ";
      }
      return text;
    };
    std::printf("%-16s | %s| %-9.1e %-9.1e | %s%-9.1e | %d\n", name.c_str(), cells(forward).c_str(), estimate,
                condition, cells(residual).c_str(), residual(P_ref), sign_iterations);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string usage = "usage: care_accuracy write|write-ill-r DIR [COUNT] | care_accuracy compare DIR";
  try {
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (args.size() >= 2 && args.size() <= 3 && (args[0] == "write" || args[0] == "write-ill-r")) {
      const bool ill_r = args[0] == "write-ill-r";
      int count = ill_r ? 16 : 12;
      if (args.size() == 3) {
        std::size_t used = 0;
        try {
          count = std::stoi(args[2], &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != args[2].size() || count < 0) throw thetad::Error("COUNT must be an integer ≥ 0, got '" + args[2] + "'");
      }
      write(args[1], ill_r ? ill_conditioned_r_problems(count) : study_problems(count));
    } else if (args.size() == 2 && args[0] == "compare") {
      compare(args[1]);
    } else {
      std::fprintf(stderr, "%s\n", usage.c_str());
      return 2;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "care_accuracy: %s\n", e.what());
    return 1;
  }
  return 0;
}
