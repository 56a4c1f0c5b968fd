#include "ready/writers/vti_file.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

#include "ready/vtk_arrays.hpp"

namespace ready {

using tinyxml2::XMLElement;

std::string ready_vti(const ReadyState& s) {
    tinyxml2::XMLDocument doc;
    XMLElement* vtk = doc.NewElement("VTKFile");
    doc.InsertEndChild(doc.NewDeclaration());
    doc.InsertEndChild(vtk);
    vtk->SetAttribute("type", "ImageData");
    vtk->SetAttribute("version", "1.0");
    vtk->SetAttribute("byte_order", "LittleEndian");
    vtk->SetAttribute("header_type", "UInt64");
    vtk->SetAttribute("compressor", "vtkZLibDataCompressor");
    XMLElement* rd = vtk->InsertNewChildElement("RD");
    rd->SetAttribute("format_version", 6);
    rd->InsertNewChildElement("description")->SetText(s.description.c_str());
    XMLElement* rule = rd->InsertNewChildElement("rule");
    rule->SetAttribute("name", s.rule_name.c_str());
    rule->SetAttribute("type", s.kernel.empty() ? "formula" : "kernel");
    rule->SetAttribute("wrap", s.wrap ? 1 : 0);
    rule->SetAttribute("neighborhood_type", "vertex");
    for (const auto& [name, value] : s.parameters) {
        XMLElement* p = rule->InsertNewChildElement("param");
        p->SetAttribute("name", name.c_str());
        char text[40];
        std::snprintf(text, sizeof text, "%.9g", value);
        p->SetText(text);
    }
    // a kernel rule: Ready's <kernel>, the whole kernel
    XMLElement* f = rule->InsertNewChildElement(s.kernel.empty() ? "formula" : "kernel");
    f->SetAttribute("number_of_chemicals", static_cast<int>(s.chemicals.size()));
    f->SetAttribute("block_size_x", s.block_x);
    f->SetAttribute("block_size_y", 1);
    f->SetAttribute("block_size_z", 1);
    if (s.kernel.empty()) f->SetAttribute("accuracy", s.accuracy.c_str());
    f->SetText((s.kernel.empty() ? s.formula : s.kernel).c_str());
    rd->InsertNewChildElement("initial_pattern_generator")->SetAttribute("apply_when_loading", "false");
    XMLElement* rs = rd->InsertNewChildElement("render_settings");
    rs->InsertNewChildElement("active_chemical")->SetAttribute("value", s.active_chemical.c_str());
    if (s.low) rs->InsertNewChildElement("low")->SetAttribute("value", *s.low);
    if (s.high) rs->InsertNewChildElement("high")->SetAttribute("value", *s.high);
    XMLElement* image = vtk->InsertNewChildElement("ImageData");
    const std::string extent = "0 " + std::to_string(s.width - 1) + " 0 " + std::to_string(s.height - 1) + " 0 " +
                               std::to_string(s.depth - 1);
    image->SetAttribute("WholeExtent", extent.c_str());
    image->SetAttribute("Origin", "0 0 0");
    image->SetAttribute("Spacing", "1 1 1");
    XMLElement* piece = image->InsertNewChildElement("Piece");
    piece->SetAttribute("Extent", extent.c_str());
    XMLElement* point_data = piece->InsertNewChildElement("PointData");
    for (std::size_t c = 0; c < s.chemicals.size(); ++c) {
        const auto& v = s.chemicals[c];
        XMLElement* a = point_data->InsertNewChildElement("DataArray");
        a->SetAttribute("type", s.float64 ? "Float64" : "Float32");
        a->SetAttribute("Name", std::string(1, static_cast<char>('a' + c)).c_str());
        a->SetAttribute("format", "binary");
        if (!v.empty()) {
            const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
            a->SetAttribute("RangeMin", *lo);
            a->SetAttribute("RangeMax", *hi);
        }
    }
    piece->InsertNewChildElement("CellData");
    tinyxml2::XMLPrinter printer;
    doc.Print(&printer);
    const std::string_view printed(printer.CStr(), static_cast<std::size_t>(printer.CStrSize() - 1));
    // Each array's text (base64: nothing in it to escape) goes into its
    // element after the document is printed, so that the printer neither
    // copies nor scans megabytes of it. The elements are the printed text's
    // "<DataArray " in order: no text of the pattern's can hold one, as the
    // printer writes its '<' as "&lt;".
    std::string out;
    std::size_t at = 0;
    for (const auto& v : s.chemicals) {
        const std::size_t open = printed.find("<DataArray ", at), close = printed.find("/>", open);
        if (open == std::string_view::npos || close == std::string_view::npos)
            throw std::logic_error("ready_vti: an array's element is not where it was put");
        const std::string text = vtk::encode_zlib_base64(v, s.float64);
        out.reserve(printed.size() + text.size() + 16 * s.chemicals.size());
        out.append(printed.substr(at, close - at)).append(">").append(text).append("</DataArray>");
        at = close + 2;
    }
    out.append(printed.substr(at));
    return out;
}

}  // namespace ready
