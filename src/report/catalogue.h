// foglab — the catalogues behind report/language.h: one per language, each a list of
// (key, text) pairs; language.cc indexes them. Not installed.
#pragma once

#include <span>
#include <string_view>

#include "foglab/report/language.h"

namespace foglab::report::detail {

struct CatalogueEntry {
  Text key;
  std::string_view text;
};

std::span<const CatalogueEntry> catalogue_en();
std::span<const CatalogueEntry> catalogue_ru();

}  // namespace foglab::report::detail
