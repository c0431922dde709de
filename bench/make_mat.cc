// Writes a lab-layout MAT v5 file (f, Y1) of white rate noise for timing
// the CLI end to end. Usage: bench_make_mat OUT.mat SAMPLES [FS_HZ]
#include <fmt/format.h>
#include <matio.h>

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "bench_support.h"

int main(int argc, char** argv) {
  CLI::App app{"Writes a lab-layout MAT v5 file (f, Y1) of white rate noise", "bench_make_mat"};
  std::string out;
  std::size_t n = 0;
  double fs = 100.0;
  app.add_option("out", out, "output MAT file")->required();
  app.add_option("samples", n, "number of samples")
      ->required()
      ->check(CLI::Range(std::size_t{1}, std::size_t{1} << 40));
  app.add_option("fs_hz", fs, "sample rate [Hz]")->check(CLI::Range(1e-6, 1e9));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help is not an error; anything else is a usage error
  }
  std::vector<double> y = foglab::bench::gyro_record(n);
  mat_t* mat = Mat_CreateVer(out.c_str(), nullptr, MAT_FT_MAT5);
  if (mat == nullptr) {
    fmt::print(stderr, "bench_make_mat: cannot create {}\n", out);
    return 1;
  }
  size_t scalar_dims[2] = {1, 1};
  size_t dims[2] = {n, 1};
  matvar_t* f = Mat_VarCreate("f", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, scalar_dims, &fs, 0);
  matvar_t* y1 = Mat_VarCreate("Y1", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, y.data(), 0);
  const bool ok = Mat_VarWrite(mat, f, MAT_COMPRESSION_NONE) == 0 &&
                  Mat_VarWrite(mat, y1, MAT_COMPRESSION_NONE) == 0;
  Mat_VarFree(f);
  Mat_VarFree(y1);
  Mat_Close(mat);
  return ok ? 0 : 1;
}
