#pragma once
// GollyGang/Ready's pattern files (.vti): VTK's XML ImageData with an <RD>
// element that holds the rule, its parameters, the start's overlays and
// Ready's drawing settings.
//
// Read (figgen render PATTERN.vti, figgen convert PATTERN.vti): a 2-D
// pattern whose rule is a formula becomes the figgen description of the
// formula scene that runs it, and, when Ready would start from the arrays
// the file stores (apply_when_loading="false"), those arrays. The arrays
// come in each encoding VTK writes: ascii, binary (base64, raw or
// zlib-compressed in blocks, with 32- or 64-bit headers) and appended
// (base64 or raw), Float32 or Float64. XML by tinyxml2, base64 by GLib,
// zlib by zlib.
//
// Written (--format vti): a run's last step as Ready writes its own files
// (binary, zlib-compressed blocks, apply_when_loading="false", the rule and
// its parameters kept), so Ready or ParaView continue from it.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "description/description.hpp"

namespace description {

// The chemicals a file stores, a, b, c, ... in order.
struct StoredStart {
    int width = 0, height = 0;
    bool float64 = false;  // Float64 arrays (else Float32)
    std::vector<std::vector<double>> chemicals;  // width * height values each, x fastest, row y = 0 first
};

struct ReadyPattern {
    std::string id;    // the file's stem, as a plain id
    std::string toml;  // the equivalent description of the formula scene
    // The stored arrays when Ready starts from them (apply_when_loading
    // is "false"); else null: the description's overlays make the start.
    std::shared_ptr<const StoredStart> start;
};

// The largest pattern file read; a larger one is refused before it is parsed.
inline constexpr std::uintmax_t max_pattern_bytes = 256u << 20;
// The most a pattern's stored arrays may take decoded (as doubles): zlib
// lets a small file hold far more. 1 GiB holds 8 chemicals of 4096 x 4096.
inline constexpr std::uintmax_t max_start_bytes = 1u << 30;

// Whether `target` names a Ready pattern file (ends in .vti).
bool is_ready_pattern(const std::string& target);

// Reads `file`. `steps` is how many steps the description runs (else
// 1000), with panels at 0, steps/2 and steps. Throws UsageError, naming the
// file, for a pattern that cannot be read or that figgen cannot run (3-D or
// 1-D, a mesh, a kernel or inbuilt rule, an unknown encoding), in one line
// that says what is not supported.
ReadyPattern read_ready_pattern(const std::filesystem::path& file, std::optional<int> steps = std::nullopt);

// The pattern as a Description, with the --set `overrides` and `seed`
// applied as to a description file; `steps` taken from an override of
// steps when one is given.
Description load_ready_pattern(const std::filesystem::path& file, const std::vector<std::string>& overrides = {},
                               std::optional<std::uint64_t> seed = std::nullopt);

// The names a formula's text holds (words of letters, digits and _): the
// parameters it may use.
std::set<std::string> formula_words(const std::string& code);

// What a VTI file of a formula run holds.
struct ReadyState {
    std::string rule_name;    // <rule name=...>
    std::string description;  // <description>
    std::string formula;
    std::string accuracy = "medium";
    bool wrap = true;
    int block_x = 4;
    std::vector<std::pair<std::string, double>> parameters;
    std::string active_chemical = "a";
    std::optional<double> low, high;  // the drawn range of the active chemical
    int width = 0, height = 0;
    bool float64 = false;
    std::vector<std::vector<double>> chemicals;  // as StoredStart
};

// The file's text: VTK XML ImageData, version 1.0, UInt64 headers, binary
// zlib-compressed blocks of 32 KiB, as VTK 9's writer makes Ready's files.
std::string ready_vti(const ReadyState& state);

}  // namespace description
