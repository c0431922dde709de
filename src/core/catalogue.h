// foglab — the catalogues behind core/language.h: one per language, each a list of
// (key, text) pairs; language.cc indexes them. Not installed.
#pragma once

#include <span>
#include <string_view>

#include "foglab/core/language.h"

namespace foglab::detail {

struct CatalogueEntry {
  Text key;
  std::string_view text;
};

std::span<const CatalogueEntry> catalogue_en();
std::span<const CatalogueEntry> catalogue_ru();

}  // namespace foglab::detail
