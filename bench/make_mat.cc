// Writes a lab-layout MAT v5 file (f, t, Y1) of white rate noise for timing
// the CLI end to end. Usage: bench_make_mat OUT.mat SAMPLES [FS_HZ]
#include <fmt/format.h>
#include <matio.h>

#include <string>
#include <vector>

#include "bench_support.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    fmt::print(stderr, "usage: bench_make_mat OUT.mat SAMPLES [FS_HZ]\n");
    return 2;
  }
  const std::size_t n = std::stoull(argv[2]);
  double fs = argc > 3 ? std::stod(argv[3]) : 100.0;
  std::vector<double> y = foglab::bench::gyro_record(n);
  mat_t* mat = Mat_CreateVer(argv[1], nullptr, MAT_FT_MAT5);
  if (mat == nullptr) return 1;
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
