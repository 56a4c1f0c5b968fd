#pragma once
// Ready's mesh files: VTK XML UnstructuredGrid (.vtu), as Ready reads and
// writes them (its IO_XML.cpp, through VTK's XML reader and writer): the
// points, the cells (with polyhedra's faces), every CellData array (Ready's
// chemicals a, b, ... are cell data) and Ready's <RD> element, whose rule
// the caller reads.
//
// A file is a stranger's: every count, offset and index is checked before
// it is used, within limits on cells, points and decoded bytes, so that a
// file that lies about its sizes, or a zlib bomb, is refused in one line
// naming the element or attribute, the value and what is allowed.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ready/vtk_arrays.hpp"
#include "sim/mesh/mesh.hpp"

namespace ready::vtu {

// What is wrong with a file, in words that quote nothing long of it.
using DataError = vtk::DataError;

// The most a file may hold.
inline constexpr std::uint64_t max_cells = 4'000'000;
inline constexpr std::uint64_t max_points = 16'000'000;
// The bytes of all its arrays together, decoded, in their own types
// (held as int64 and double: up to 8 times that for a UInt8 array).
inline constexpr std::uint64_t max_decoded_bytes = std::uint64_t{1} << 30;
// The file's text.
inline constexpr std::uint64_t max_file_bytes = std::uint64_t{256} << 20;

// One CellData array: a value (or `components` values) a cell.
struct CellArray {
    std::string name;
    int components = 1;   // 1 to 64
    bool float64 = false; // Float64, else Float32
    std::vector<double> values;  // cells x components, a cell's components together
};

struct UnstructuredGrid {
    sim::mesh::Mesh mesh;
    bool points_float64 = false;       // the points are Float64, else Float32
    std::vector<CellArray> cell_data;  // <CellData>'s arrays, in the file's order
    std::string rd;                    // the <RD> element's XML text; empty when the file has none
};

// The grid in a .vtu file's text: one <Piece>, its arrays in any encoding
// VTK writes (ascii; binary or appended, base64 or raw; zlib blocks or
// not; UInt32 or UInt64 headers), its cells of types 5, 7, 9, 10, 11, 12,
// 13, 14 or 42 (sim::mesh::cell_type), the points finite. <PointData> and
// <FieldData> are not read. Throws DataError.
UnstructuredGrid read_vtu(std::string_view text);

// The grid as VTK 9's writer makes Ready's files (version 1.0, UInt64
// headers, each array binary in zlib blocks; connectivity, offsets, faces
// and faceoffsets Int64, types UInt8), with `grid.rd` as its <RD>, so that
// Ready (and VTK) read it back. Points Float32 unless points_float64, each
// array as its float64 says: every value round trips when it is of that
// type. Throws std::invalid_argument for a mesh sim::mesh::check refuses,
// an array of the wrong length, or an rd that is not one <RD> element.
std::string write_vtu(const UnstructuredGrid& grid);

}  // namespace ready::vtu
