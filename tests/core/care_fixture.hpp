#pragma once

// The fixture files of the CARE tests (tests/fixtures/carex, tests/fixtures/care_reference).

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <Eigen/Dense>

namespace thetad::testing {

// One CARE problem as scripts/make_carex_fixtures.py and scripts/make_care_reference_fixtures.py write
// it: '#' comments, 'name NAME', and blocks 'KEY ROWS COLS' (KEY upper case) of ROWS lines.
struct Fixture {
  std::string name;
  std::map<std::string, Eigen::MatrixXd> matrices;
};

inline Fixture read_fixture(const std::filesystem::path& path) {
  std::ifstream in(path);
  Fixture fixture;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream header(line);
    std::string key;
    header >> key;
    if (key == "name") {
      header >> fixture.name;
    } else if (key.size() > 0 && std::isupper(static_cast<unsigned char>(key[0]))) {
      Eigen::Index rows = 0;
      Eigen::Index cols = 0;
      header >> rows >> cols;
      Eigen::MatrixXd M(rows, cols);
      for (Eigen::Index i = 0; i < rows; ++i)
        for (Eigen::Index j = 0; j < cols; ++j) in >> M(i, j);
      fixture.matrices[key] = M;
    }
  }
  return fixture;
}

}  // namespace thetad::testing
