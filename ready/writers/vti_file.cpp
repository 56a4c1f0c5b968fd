#include "ready/writers/vti_file.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>

#include "ready/vtk_arrays.hpp"
#include "ready/writers/rd_element.hpp"

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
    add_rd_element(vtk, s);
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
