// The fuzz entries for Ready's files (fuzz_entries.hpp): VTK's array
// encodings and the <RD> element of a pattern.
#include <glib.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "description/description.hpp"
#include "description/plain_name.hpp"
#include "fuzz/fuzz_entries.hpp"
#include "ready/pattern.hpp"
#include "ready/vtk_arrays.hpp"
#include "scenes/scene.hpp"

namespace fuzz {
namespace {

// Reads the fuzz input from the front, a byte or a word at a time; zeros
// once it is used up.
struct Bytes {
    const std::uint8_t* data;
    std::size_t size;
    std::uint8_t byte() {
        if (size == 0) return 0;
        --size;
        return *data++;
    }
    std::uint64_t word() {
        std::uint64_t w = 0;
        for (int i = 0; i < 8; ++i) w |= std::uint64_t{byte()} << (8 * i);
        return w;
    }
    std::string rest() {
        std::string s(reinterpret_cast<const char*>(data), size);
        size = 0;
        return s;
    }
};

std::string base64(const std::string& bytes) {
    gchar* text = g_base64_encode(reinterpret_cast<const guchar*>(bytes.data()), bytes.size());
    std::string s(text);
    g_free(text);
    return s;
}

void put_word(std::string& out, std::uint64_t w, int header) {
    char b[8];
    std::memcpy(b, &w, 8);  // little-endian, as VTK's files are
    out.append(b, static_cast<std::size_t>(header));
}

// A header word as a liar would pick it: near a power of two, or past one.
std::uint64_t lie(Bytes& in, std::uint64_t honest) {
    switch (in.byte() % 6) {
    case 0: return honest;
    case 1: return honest + (std::uint64_t{1} << 63);
    case 2: return (std::uint64_t{1} << 63) - in.byte();
    case 3: return ~std::uint64_t{0} - in.byte();
    case 4: return honest + in.byte() - 128;
    default: return in.word();
    }
}

// The same Ready file's text, its <RD> spliced from the input: fields
// split at NUL bytes. Field 0 is the formula, 1 the rule's name; then each
// field is a parameter ("p" name "=" value), an overlay ("o" then bytes
// that pick its chemical, operation, fill and shape, then a parameter's
// name) or render settings ("r" then the active chemical and a colour
// map). Text goes in escaped, so the XML stays well-formed and the
// reader, not the XML parser, meets what a name or formula holds.
std::string escaped(std::string_view text) {
    std::string out;
    for (char c : text) {
        const auto b = static_cast<unsigned char>(c);
        if (c == '&') out += "&amp;";
        else if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '"') out += "&quot;";
        else if (b < 0x20 && c != '\n' && c != '\t') out += "&#" + std::to_string(b) + ";";
        else out += c;
    }
    return out;
}

std::string pattern_from_fields(std::string_view input) {
    std::vector<std::string_view> fields;
    while (true) {
        const std::size_t end = input.find('\0');
        fields.push_back(input.substr(0, end));
        if (end == std::string_view::npos || fields.size() >= 64) break;
        input.remove_prefix(end + 1);
    }
    const auto field = [&](std::size_t i) { return i < fields.size() ? fields[i] : std::string_view(); };
    std::string params = "<param name=\"timestep\">0.1</param>", overlays, render;
    static const char* const operations[] = {"overwrite", "add", "subtract", "multiply", "divide"};
    static const char* const fills[] = {
        "<constant value=\"0.5\" />", "<white_noise low=\"0\" high=\"1\" />", "<perlin_noise scale=\"8\" num_octaves=\"3\" />",
        "<gaussian height=\"1\" sigma=\"0.1\"><point3D x=\"0.5\" y=\"0.5\" z=\"0\" /></gaussian>",
        "<sine phase=\"0\" amplitude=\"1\"><point3D x=\"0\" y=\"0\" z=\"0\" /><point3D x=\"1\" y=\"1\" z=\"0\" /></sine>",
        "<other_chemical chemical=\"b\" />"};
    static const char* const shapes[] = {"<everywhere />", "<circle radius=\"0.2\"><point3D x=\"0.5\" y=\"0.5\" z=\"0\" /></circle>",
                                         "<pixel x=\"3\" y=\"2\" z=\"0\" />", "<pixel x=\"3\" y=\"2\" z=\"1\" />",
                                         "<rectangle><point3D x=\"0\" y=\"0\" z=\"0\" /><point3D x=\"0.5\" y=\"1\" z=\"0\" /></rectangle>"};
    static const char* const maps[] = {"spectral", "spectral reversed", "inferno", "terrain", "HSV blend", "grey"};
    for (std::size_t i = 2; i < fields.size(); ++i) {
        const std::string_view f = fields[i];
        if (f.empty()) continue;
        const std::string_view body = f.substr(1);
        if (f[0] == 'p') {
            const std::size_t eq = body.find('=');
            params += "<param name=\"" + escaped(body.substr(0, eq)) + "\">" +
                      escaped(eq == std::string_view::npos ? "1" : body.substr(eq + 1)) + "</param>";
        } else if (f[0] == 'o' && body.size() >= 4) {
            const auto b = [&](std::size_t k) { return static_cast<unsigned char>(body[k]); };
            const std::string fill = b(2) % 7 == 6 ? "<parameter name=\"" + escaped(body.substr(4)) + "\" />"
                                                   : fills[b(2) % 7 % 6];
            overlays += std::string("<overlay chemical=\"") + static_cast<char>('a' + b(0) % 3) + "\"><" +
                        operations[b(1) % 5] + " />" + fill + shapes[b(3) % 5] + "</overlay>";
        } else if (f[0] == 'r' && body.size() >= 2) {
            render = std::string("<render_settings><active_chemical value=\"") +
                     static_cast<char>('a' + static_cast<unsigned char>(body[0]) % 3) + "\" /><colormap value=\"" +
                     maps[static_cast<unsigned char>(body[1]) % 6] + "\" /><low value=\"" + escaped(body.substr(2)) +
                     "\" /></render_settings>";
        }
    }
    const std::string apply = overlays.empty() ? "false" : "true";
    std::string text = "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" "
                       "header_type=\"UInt64\">\n<RD format_version=\"6\">\n<rule name=\"" +
                       escaped(field(1)) + "\" type=\"formula\" wrap=\"1\">" + params +
                       "<formula number_of_chemicals=\"2\">" + escaped(field(0)) +
                       "</formula></rule>\n<initial_pattern_generator apply_when_loading=\"" + apply + "\">" +
                       overlays + "</initial_pattern_generator>\n" + render +
                       "</RD>\n<ImageData WholeExtent=\"0 7 0 5 0 0\" Origin=\"0 0 0\" Spacing=\"1 1 1\">"
                       "<Piece Extent=\"0 7 0 5 0 0\"><PointData>";
    for (const char* chem : {"a", "b"}) {
        text += std::string("<DataArray type=\"Float32\" Name=\"") + chem + "\" format=\"ascii\">";
        for (int i = 0; i < 48; ++i) text += std::to_string(i % 7) + " ";
        text += "</DataArray>";
    }
    return text + "</PointData></Piece></ImageData>\n</VTKFile>\n";
}

}  // namespace

Outcome vtk_arrays(const std::uint8_t* data, std::size_t size) {
    Bytes in{data, size};
    const std::uint8_t pick = in.byte();
    const int header = pick & 1 ? 8 : 4;
    const bool compressed = (pick & 2) != 0, as_base64 = (pick & 4) != 0, float64 = (pick & 8) != 0;
    const bool ascii = (pick & 0x30) == 0x30;
    const std::size_t block = 1 + in.byte() % 64;
    const std::uint8_t lies = in.byte();  // which header words lie (bit per word), and how
    const std::string payload = in.rest();
    const std::uint64_t honest = payload.size() - payload.size() % (float64 ? 8 : 4);
    const std::string values = payload.substr(0, static_cast<std::size_t>(honest));
    Bytes liar{reinterpret_cast<const std::uint8_t*>(payload.data()), payload.size()};  // lies drawn from the payload too
    const auto maybe_lie = [&](int bit, std::uint64_t word) { return (lies >> bit) & 1 ? lie(liar, word) : word; };
    try {
        std::vector<std::uint8_t> bytes;
        if (ascii) {
            const std::uint64_t count = lies;
            const auto numbers = ready::vtk::decode_ascii(payload, count, float64);
            if (numbers.size() != count) throw std::logic_error("an ascii array was read to another count");
            return Outcome::accepted;
        }
        const std::uint64_t expected = maybe_lie(7, honest);
        if (!compressed) {
            std::string raw;
            put_word(raw, maybe_lie(0, honest), header);
            raw += values;
            bytes = as_base64 ? ready::vtk::decode_base64(base64(raw), {header, false}, expected)
                              : ready::vtk::decode_raw(raw, {header, false}, expected);
        } else {
            // Honest blocks of the payload, zlib-compressed; then the header, each word maybe a lie.
            std::string head, body;
            const std::uint64_t count = (values.size() + block - 1) / block;
            put_word(head, maybe_lie(1, count), header);
            put_word(head, maybe_lie(2, block), header);
            put_word(head, maybe_lie(3, values.size() % block), header);
            for (std::uint64_t i = 0; i < count; ++i) {
                const std::string chunk = values.substr(static_cast<std::size_t>(i * block), block);
                uLongf n = compressBound(static_cast<uLong>(chunk.size()));
                std::string z(n, '\0');
                compress2(reinterpret_cast<Bytef*>(z.data()), &n, reinterpret_cast<const Bytef*>(chunk.data()),
                          static_cast<uLong>(chunk.size()), 1);
                z.resize(n);
                put_word(head, maybe_lie(4 + static_cast<int>(i % 3), n), header);
                body += (lies & 0x40) && i == 0 ? z.substr(0, z.size() / 2) : z;  // a block cut short
            }
            bytes = as_base64 ? ready::vtk::decode_base64(base64(head) + " \n" + base64(body), {header, true}, expected)
                              : ready::vtk::decode_raw(head + body, {header, true}, expected);
        }
        // What decodes is exactly what was encoded, when nothing lied.
        if (lies == 0 && std::string(bytes.begin(), bytes.end()) != values)
            throw std::logic_error("an honest array decoded to other bytes");
        if (bytes.size() != expected) throw std::logic_error("an array decoded to another size than its extent's");
        (void)ready::vtk::numbers_of(bytes, float64);
        return Outcome::accepted;
    } catch (const ready::vtk::DataError& e) {
        if (std::string_view(e.what()).find('\n') != std::string_view::npos)
            throw std::logic_error("a refusal of more than one line");
        return Outcome::refused;
    }
}

Outcome ready_pattern(const std::uint8_t* data, std::size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    // A whole file (Ready's own, as seeds) begins with markup; anything
    // else is the fields of an <RD> spliced into a small pattern.
    const std::size_t first = input.find_first_not_of(" \t\r\n");
    const bool whole = first != std::string_view::npos && input[first] == '<';
    const std::string text = whole ? std::string(input) : pattern_from_fields(input);
    try {
        // Read without its arrays first; decoded only when the grid is small.
        ready::Pattern pattern = ready::read_pattern_text(text, "fuzz.vti");
        const long long cells = pattern.description["params"]["width"].value_or(0LL) *
                                pattern.description["params"]["height"].value_or(0LL);
        if (pattern.starts_from_arrays && cells <= 65536)
            pattern = ready::read_pattern_text(text, "fuzz.vti", {std::nullopt, true});
        // convert's text reads back as the same table: no name or formula escapes its string.
        const std::string converted = ready::converted_text(pattern, "fuzz.vti");
        toml::table again;
        try {
            again = toml::parse(converted);
        } catch (const toml::parse_error& e) {
            throw std::logic_error(std::string("convert wrote TOML that does not parse: ") + std::string(e.description()));
        }
        if (again != pattern.description) throw std::logic_error("convert wrote a description that reads back otherwise");
        description::Description d = description::description_from_table(pattern.description, "fuzz.vti", pattern.origins);
        d.stored_start = pattern.start;
        description::at_source(d, [&] { return scenes::read_scene(d, scenes::SceneOptions{0.3, false}); });
        return Outcome::accepted;
    } catch (const description::UsageError& e) {
        const std::string message = e.what();
        if (message.find('\n') != std::string::npos || message.find('\r') != std::string::npos)
            throw std::logic_error("a refusal of more than one line");
        return Outcome::refused;
    }
}

}  // namespace fuzz
