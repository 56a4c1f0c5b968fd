#include "ready/writers/rd_element.hpp"

#include <cstdio>

namespace ready {

using tinyxml2::XMLElement;

void add_rd_element(tinyxml2::XMLNode* parent, const ReadyState& s) {
    XMLElement* rd = parent->GetDocument()->NewElement("RD");
    parent->InsertEndChild(rd);
    rd->SetAttribute("format_version", 6);
    rd->InsertNewChildElement("description")->SetText(s.description.c_str());
    XMLElement* rule = rd->InsertNewChildElement("rule");
    rule->SetAttribute("name", s.rule_name.c_str());
    rule->SetAttribute("type", s.kernel.empty() ? "formula" : "kernel");
    if (!s.mesh) rule->SetAttribute("wrap", s.wrap ? 1 : 0);  // a mesh has no edges to wrap
    rule->SetAttribute("neighborhood_type", s.neighborhood.c_str());
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
    if (!s.mesh) {  // an image's work items; a mesh's are its cells, one each
        f->SetAttribute("block_size_x", s.block_x);
        f->SetAttribute("block_size_y", 1);
        f->SetAttribute("block_size_z", 1);
        if (s.kernel.empty()) f->SetAttribute("accuracy", s.accuracy.c_str());
    }
    f->SetText((s.kernel.empty() ? s.formula : s.kernel).c_str());
    rd->InsertNewChildElement("initial_pattern_generator")->SetAttribute("apply_when_loading", "false");
    XMLElement* rs = rd->InsertNewChildElement("render_settings");
    rs->InsertNewChildElement("active_chemical")->SetAttribute("value", s.active_chemical.c_str());
    if (s.low) rs->InsertNewChildElement("low")->SetAttribute("value", *s.low);
    if (s.high) rs->InsertNewChildElement("high")->SetAttribute("value", *s.high);
}

}  // namespace ready
