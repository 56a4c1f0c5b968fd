#pragma once
// The parsers that read what users type, as fuzz entries: each takes
// raw bytes, feeds them to the parser (and a little beyond it, to the first
// use of what was parsed) and says whether the input was accepted or refused
// with the parser's own error. Anything else, an exception of another type,
// a crash or undefined behaviour, is a bug. libFuzzer calls them from
// tests/fuzz/fuzz_*.cpp; the ordinary suite replays the committed corpus and
// regressions through them (tests/fuzz/test_fuzz_corpus.cpp).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fuzz {

enum class Outcome { accepted, refused };

// A figure description in TOML (description::parse_description), then its
// scene's phase 1 (scenes::read_scene): every setting read and checked.
Outcome description(const std::uint8_t* data, std::size_t size);
// --set assignments, one per line, applied to a small diffusion description
// (description::apply_override through description::parse_description), then its
// [params] read as the diffusion scene reads them.
Outcome set_assignments(const std::uint8_t* data, std::size_t size);
// A snowflake rule code (sim::SnowflakeRule::parse); an accepted rule grows a
// flake for 8 steps.
Outcome snowflake_rule(const std::uint8_t* data, std::size_t size);
// An L-system: the first line the axiom, each further line a rule "X -> ...";
// an accepted system is counted to depth 4, and drawn by both turtles when
// that is under 20,000 segments.
Outcome lsystem(const std::uint8_t* data, std::size_t size);

// A formula rule's code (sim::formula::Run): the first byte picks the
// rule's settings, the rest is the formula. An accepted formula runs 3
// steps on an 8 x 8 grid; refused: sim::formula::FormulaError.
Outcome formula(const std::uint8_t* data, std::size_t size);

// A figure id as `--set id=` gives it (any bytes: NUL, newlines, invalid
// UTF-8): accepted only when it names a file inside the output folder (no
// separator, not hidden, not "." or ".."), and a refusal's message, as
// figgen prints it, is one line without control or bidirectional characters.
Outcome output_name(const std::uint8_t* data, std::size_t size);

// A work item's part or a parts manifest, as merge and resume read them. The
// first byte picks what the rest is: a manifest's text (app::json_bounded,
// then its values shown as a refusal shows them), a part's bytes whole
// (app::result_of_part), or a result that is put in a part with its true
// hash, so that the scene's check_result is reached; the second byte picks
// a small figure with work items (tc7-phase, gs-atlas, bd-roughness,
// pc-threshold, tc7-ex1), the third its item. Refused: app::MalformedData,
// in one clean line.
Outcome parts(const std::uint8_t* data, std::size_t size);

// A title drawn as the figure's caption, then as a panel's title: the first
// byte picks the language (bits 1-2: none, "ja", "zh-cn", "ko") and how the
// rest is read (bit 0: as bytes, any at all; set: as 4-byte little-endian
// code points, each modulo 0x110000, surrogates and noncharacters too, put
// into UTF-8 as they are); the second the room, 8 to 1028 pixels. Accepted
// when the description reader takes it as `--set title=` and its caption
// fits a figure that wide; whatever the reader says, the text also goes
// through wrap, line_ink and text_clash as drawn, and a wrapped caption
// must hold the text's every character but the spaces and line feeds where
// it breaks.
Outcome caption_text(const std::uint8_t* data, std::size_t size);

// VTK's array encodings (ready/vtk_arrays.hpp), structure-aware: the
// first byte picks the header's word size, zlib blocks or none, base64 or
// raw, Float32 or Float64 (or ascii), the second the block size, the third
// which header words lie and how (near 2^63, past 2^64, a word of the
// input); the rest is the values, compressed in honest blocks before the
// lies go in. Accepted: decoded to exactly its extent's bytes (the
// values themselves when nothing lied); refused: ready::vtk::DataError.
Outcome vtk_arrays(const std::uint8_t* data, std::size_t size);

// A Ready pattern (ready/pattern.hpp): a whole file when it begins with
// markup (Ready's own files are the seeds), else fields split at NUL that
// are put, escaped, into a small pattern's <RD>: the formula, the rule's
// name, then parameters ("pNAME=VALUE"), overlays ("o" and four bytes that
// pick chemical, operation, fill and shape, then a parameter's name) and
// render settings ("r..."). An accepted pattern's converted text must read
// back as the same table, and its scene's phase 1 pass; refused:
// description::UsageError in one line.
Outcome ready_pattern(const std::uint8_t* data, std::size_t size);

// A kernel rule (sim/kernel/): the first byte picks the run (chemicals,
// numbers, blocks, a 1-D, 2-D or 3-D grid, or a small mesh), the rest is
// the kernel. An accepted kernel runs 2 steps (a fault it meets stops it
// with its own error); refused: sim::kernel::KernelError.
Outcome kernel(const std::uint8_t* data, std::size_t size);
// A mesh file (ready/vtu.hpp): read, its neighbours by vertex, edge and
// face, and written back. Refused: ready::vtu::DataError, or a mesh of
// more than one cell type (std::invalid_argument, as Ready refuses it).
Outcome mesh(const std::uint8_t* data, std::size_t size);

struct Target {
    const char* name;  // the folder under tests/fuzz/corpus/ and regressions/
    Outcome (*entry)(const std::uint8_t*, std::size_t);
};
const std::vector<Target>& targets();

}  // namespace fuzz
