#pragma once
// Ready's <RD> element of a run's state, as Ready writes it in front of the
// grid of its .vti and .vtu files: the description, the rule (its name,
// kind, parameters and whole formula or kernel), an initial pattern
// generator that is not applied on loading (the stored cells are the
// start), and the drawn range.

#include <tinyxml2.h>

#include "ready/state.hpp"

namespace ready {

// Adds the element to `parent` (the <VTKFile>, or a document of its own).
void add_rd_element(tinyxml2::XMLNode* parent, const ReadyState& state);

}  // namespace ready
