#include "ready/writers/vtu_file.hpp"

#include <stdexcept>

#include "ready/vtu.hpp"
#include "ready/writers/rd_element.hpp"

namespace ready {

std::string ready_vtu(const ReadyState& s) {
    if (!s.mesh) throw std::invalid_argument("ready_vtu: the state is not a mesh's");
    vtu::UnstructuredGrid grid;
    grid.mesh = *s.mesh;
    grid.points_float64 = s.points_float64;
    for (std::size_t c = 0; c < s.chemicals.size(); ++c)
        grid.cell_data.push_back({.name = std::string(1, static_cast<char>('a' + c)),
                                  .components = 1,
                                  .float64 = s.float64,
                                  .values = s.chemicals[c]});
    tinyxml2::XMLDocument rd;
    add_rd_element(&rd, s);
    tinyxml2::XMLPrinter printer;
    rd.Print(&printer);
    grid.rd.assign(printer.CStr(), static_cast<std::size_t>(printer.CStrSize() - 1));
    return vtu::write_vtu(grid);
}

}  // namespace ready
