#pragma once
// GollyGang/Ready's pattern files (.vti): VTK's XML ImageData with an <RD>
// element that holds the rule, its parameters, the start's overlays and
// Ready's drawing settings.
//
// A 2-D pattern whose rule is a formula becomes, as data, the description
// of the formula scene that runs it: a table, never a text parsed again,
// with each key's origin an element of the file. When Ready starts from
// the arrays the file stores (apply_when_loading="false"), a render reads
// those too (ready/vtk_arrays.hpp decodes them); nothing else decodes them.
// XML by tinyxml2.
//
// A file is a stranger's: what it says is checked before it is used, and
// a message about it names its elements, never quoting more of it than a
// short name, escaped.

#include <toml++/toml.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "description/description.hpp"
#include "description/stored_start.hpp"
#include "description/stored_mesh.hpp"

namespace ready {

// What kind of Ready file a target names, by its extension in any case.
enum class FileKind { none, image, mesh };  // not Ready's; .vti; .vtu
FileKind file_kind(const std::string& target);

struct Pattern {
    std::string id;             // the file's stem, as a plain id
    toml::table description;    // the description of the formula scene that runs it
    // Where each key was given ("params.k" -> "P.vti <param name=\"k\">"),
    // as description::Description::origins.
    std::map<std::string, std::string> origins;
    std::vector<std::string> notes;  // what a converted description says in comments
    // The stored arrays when Ready starts from them: decoded when they
    // were asked for, else their shape alone; null when Ready does not
    // start from them (the description's overlays make the start).
    std::shared_ptr<const description::StoredStart> start;
    bool starts_from_arrays = false;  // whether Ready starts from the stored arrays
    // A mesh pattern's mesh and the chemicals its cells hold (read whole).
    std::shared_ptr<const description::StoredMesh> mesh;
};

// The largest pattern file read; a larger one is refused before it is parsed.
inline constexpr std::uintmax_t max_pattern_bytes = 256u << 20;
// The most a pattern's stored arrays may take decoded (as doubles): zlib
// lets a small file hold far more. 1 GiB holds 8 chemicals of 4096 x 4096.
inline constexpr std::uintmax_t max_start_bytes = 1u << 30;

struct ReadOptions {
    std::optional<int> steps;    // how many steps the description runs (else 1000)
    bool decode_arrays = false;  // read the stored arrays, when Ready starts from them
};

// Reads `file`. Panels at 0, steps/2 and steps. Throws FileError, naming
// the file, for a pattern that cannot be read or that figgen cannot run
// (a mesh, an inbuilt rule other than Gray-Scott, an unknown encoding), in
// one line that says what is not supported.
Pattern read_pattern(const std::filesystem::path& file, const ReadOptions& options = {});

// The arrays `d` (read by load_pattern without them) starts from,
// decoded from its file now: after its figure was checked and its memory
// estimated. Throws FileError for arrays that do not decode.
void decode_stored_start(description::Description& d);

// The same from the file's text, read already; `file` names it.
Pattern read_pattern_text(const std::string& text, const std::filesystem::path& file, const ReadOptions& options = {});

// The pattern as a Description that runs it, with its stored arrays when
// `decode_arrays` (a render; not `describe`), the --set `overrides` and
// `seed` applied as to a description file (`steps` taken from an override
// of steps when one is given).
description::Description load_pattern(const std::filesystem::path& file,
                                      const std::vector<std::string>& overrides = {},
                                      std::optional<std::uint64_t> seed = std::nullopt, bool decode_arrays = true);

// The pattern's description as TOML text (figgen convert), its notes as
// comments first; it reads back as `pattern.description`.
std::string converted_text(const Pattern& pattern, const std::filesystem::path& file);

}  // namespace ready
