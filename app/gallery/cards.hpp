#pragma once
// One figure's card on the gallery's page (app/gallery/cards.cpp).

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "app/gallery/folder.hpp"

namespace app::gallery {

// Figure `id`'s card, from its metadata `meta`; writes its thumbnail (and
// poster). A PNG whose header claims more than `max_memory` allows is
// named on the card instead; a file that cannot be read throws.
std::string card_html(const Folders& folders, std::uint64_t max_memory, const std::string& id,
                      const nlohmann::json& meta);

// `text` with HTML's five special characters escaped.
std::string escape(const std::string& text);

}  // namespace app::gallery
