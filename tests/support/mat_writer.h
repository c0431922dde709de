// Test support: writing MAT files of any variable class with matio (the
// reader tests and the hostile-input catalogue build their inputs with it).
#pragma once

#include <gtest/gtest.h>
#include <matio.h>

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

namespace foglab::test {

template <typename T>
constexpr matio_classes mat_class_of() {
  if constexpr (std::is_same_v<T, double>) return MAT_C_DOUBLE;
  if constexpr (std::is_same_v<T, float>) return MAT_C_SINGLE;
  if constexpr (std::is_same_v<T, std::int8_t>) return MAT_C_INT8;
  if constexpr (std::is_same_v<T, std::uint8_t>) return MAT_C_UINT8;
  if constexpr (std::is_same_v<T, std::int16_t>) return MAT_C_INT16;
  if constexpr (std::is_same_v<T, std::uint16_t>) return MAT_C_UINT16;
  if constexpr (std::is_same_v<T, std::int32_t>) return MAT_C_INT32;
  if constexpr (std::is_same_v<T, std::uint32_t>) return MAT_C_UINT32;
  if constexpr (std::is_same_v<T, std::int64_t>) return MAT_C_INT64;
  if constexpr (std::is_same_v<T, std::uint64_t>) return MAT_C_UINT64;
  return MAT_C_EMPTY;
}

template <typename T>
constexpr matio_types mat_type_of() {
  if constexpr (std::is_same_v<T, double>) return MAT_T_DOUBLE;
  if constexpr (std::is_same_v<T, float>) return MAT_T_SINGLE;
  if constexpr (std::is_same_v<T, std::int8_t>) return MAT_T_INT8;
  if constexpr (std::is_same_v<T, std::uint8_t>) return MAT_T_UINT8;
  if constexpr (std::is_same_v<T, std::int16_t>) return MAT_T_INT16;
  if constexpr (std::is_same_v<T, std::uint16_t>) return MAT_T_UINT16;
  if constexpr (std::is_same_v<T, std::int32_t>) return MAT_T_INT32;
  if constexpr (std::is_same_v<T, std::uint32_t>) return MAT_T_UINT32;
  if constexpr (std::is_same_v<T, std::int64_t>) return MAT_T_INT64;
  if constexpr (std::is_same_v<T, std::uint64_t>) return MAT_T_UINT64;
  return MAT_T_UNKNOWN;
}

/// Writes variables into one MAT file (closed by close() or the destructor).
class MatWriter {
 public:
  MatWriter(const std::string& path, mat_ft version,
            matio_compression compression = MAT_COMPRESSION_NONE)
      : compression_(compression) {
    mat_ = Mat_CreateVer(path.c_str(), nullptr, version);
    EXPECT_NE(mat_, nullptr) << "cannot create " << path;
  }
  ~MatWriter() { close(); }
  MatWriter(const MatWriter&) = delete;
  MatWriter& operator=(const MatWriter&) = delete;

  void close() {
    if (mat_ != nullptr) Mat_Close(mat_);
    mat_ = nullptr;
  }

  /// A column (or, with `row`, a row) vector of T's class.
  template <typename T>
  void vector(const std::string& name, std::vector<T> data, bool row = false) {
    std::size_t dims[2] = {row ? 1 : data.size(), row ? data.size() : 1};
    write(
        Mat_VarCreate(name.c_str(), mat_class_of<T>(), mat_type_of<T>(), 2, dims, data.data(), 0));
  }
  void scalar(const std::string& name, double value) { vector(name, std::vector<double>{value}); }
  void matrix(const std::string& name, std::size_t rows, std::size_t cols) {
    std::vector<double> data(rows * cols, 1.0);
    std::size_t dims[2] = {rows, cols};
    write(Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, data.data(), 0));
  }
  void empty(const std::string& name) {
    std::size_t dims[2] = {0, 0};
    write(Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, nullptr, 0));
  }
  /// A complex column vector (real and imaginary parts of equal length).
  void complex_vector(const std::string& name, std::vector<double> re, std::vector<double> im) {
    mat_complex_split_t split = {re.data(), im.data()};
    std::size_t dims[2] = {re.size(), 1};
    write(Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, &split, MAT_F_COMPLEX));
  }
  void text(const std::string& name, const std::string& value) {
    std::vector<char> data(value.begin(), value.end());
    std::size_t dims[2] = {1, value.size()};
    write(Mat_VarCreate(name.c_str(), MAT_C_CHAR, MAT_T_UTF8, 2, dims, data.data(), 0));
  }
  void logical(const std::string& name, std::size_t n) {
    std::vector<std::uint8_t> data(n, 1);
    std::size_t dims[2] = {n, 1};
    write(
        Mat_VarCreate(name.c_str(), MAT_C_UINT8, MAT_T_UINT8, 2, dims, data.data(), MAT_F_LOGICAL));
  }
  /// An n x 1 sparse column with every other element set.
  void sparse(const std::string& name, std::size_t n) {
    std::vector<mat_uint32_t> ir;
    std::vector<double> data;
    for (std::size_t i = 0; i < n; i += 2) {
      ir.push_back(static_cast<mat_uint32_t>(i));
      data.push_back(1.0 + static_cast<double>(i));
    }
    std::vector<mat_uint32_t> jc = {0, static_cast<mat_uint32_t>(ir.size())};
    mat_sparse_t s{};
    s.nzmax = ir.size();
    s.nir = ir.size();
    s.ir = ir.data();
    s.njc = jc.size();
    s.jc = jc.data();
    s.ndata = data.size();
    s.data = data.data();
    std::size_t dims[2] = {n, 1};
    write(
        Mat_VarCreate(name.c_str(), MAT_C_SPARSE, MAT_T_DOUBLE, 2, dims, &s, MAT_F_DONT_COPY_DATA));
  }
  /// A 1x1 struct whose field `data` holds `values` as a column.
  void structure(const std::string& name, std::vector<double> values) {
    const char* fields[] = {"data"};
    std::size_t dims[2] = {1, 1};
    matvar_t* var = Mat_VarCreateStruct(name.c_str(), 2, dims, fields, 1);
    std::size_t vdims[2] = {values.size(), 1};
    Mat_VarSetStructFieldByName(
        var, "data", 0,
        Mat_VarCreate("data", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, vdims, values.data(), 0));
    write(var);
  }
  /// A 1 x n structure array with `fields` fields, every value an empty
  /// double (no fields at all with 0).
  void structure_array(const std::string& name, std::size_t n, std::size_t fields) {
    std::vector<std::string> names;
    std::vector<const char*> pointers;
    for (std::size_t f = 0; f < fields; ++f) names.push_back("field" + std::to_string(f));
    for (const std::string& field : names) pointers.push_back(field.c_str());
    std::size_t dims[2] = {1, n};
    matvar_t* var =
        Mat_VarCreateStruct(name.c_str(), 2, dims, fields > 0 ? pointers.data() : nullptr,
                            static_cast<unsigned>(fields));
    std::size_t empty[2] = {0, 0};
    for (std::size_t i = 0; i < n; ++i) {
      for (const std::string& field : names) {
        Mat_VarSetStructFieldByName(
            var, field.c_str(), i,
            Mat_VarCreate(nullptr, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, empty, nullptr, 0));
      }
    }
    write(var);
  }
  /// A 1 x n cell array of empty doubles.
  void empty_cells(const std::string& name, std::size_t n) {
    std::size_t dims[2] = {1, n};
    matvar_t* var = Mat_VarCreate(name.c_str(), MAT_C_CELL, MAT_T_CELL, 2, dims, nullptr, 0);
    std::size_t empty[2] = {0, 0};
    for (std::size_t i = 0; i < n; ++i) {
      Mat_VarSetCell(var, static_cast<int>(i),
                     Mat_VarCreate(nullptr, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, empty, nullptr, 0));
    }
    write(var);
  }
  /// A 1x1 cell holding `values` as a column.
  void cell(const std::string& name, std::vector<double> values) {
    std::size_t dims[2] = {1, 1};
    matvar_t* var = Mat_VarCreate(name.c_str(), MAT_C_CELL, MAT_T_CELL, 2, dims, nullptr, 0);
    std::size_t vdims[2] = {values.size(), 1};
    Mat_VarSetCell(var, 0,
                   Mat_VarCreate(nullptr, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, vdims, values.data(), 0));
    write(var);
  }

 private:
  void write(matvar_t* var) {
    ASSERT_NE(var, nullptr);
    EXPECT_EQ(Mat_VarWrite(mat_, var, compression_), 0) << var->name;
    Mat_VarFree(var);
  }

  mat_t* mat_ = nullptr;
  matio_compression compression_;
};

}  // namespace foglab::test
