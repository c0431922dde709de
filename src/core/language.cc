#include "foglab/core/language.h"

#include <array>
#include <cctype>
#include <string>

#include "catalogue.h"
#include "foglab/core/error.h"

#include <fmt/args.h>
#include <fmt/format.h>

namespace foglab {
namespace {

using Index = std::array<std::string_view, static_cast<std::size_t>(Text::count_)>;

Index index_of(std::span<const detail::CatalogueEntry> entries) {
  Index index{};
  for (const auto& e : entries) index[static_cast<std::size_t>(e.key)] = e.text;
  return index;
}

}  // namespace

std::string_view to_string(Language language) { return language == Language::ru ? "ru" : "en"; }

std::string_view html_lang(Language language) { return to_string(language); }

Language language_from_string(std::string_view text) {
  std::string lower(text);
  for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (lower == "en") return Language::en;
  if (lower == "ru") return Language::ru;
  throw UsageError("the report's language is 'en' or 'ru', got '" + std::string(text) + "'");
}

std::string_view text(Language language, Text key) {
  static const Index en = index_of(detail::catalogue_en());
  static const Index ru = index_of(detail::catalogue_ru());
  const Index& index = language == Language::ru ? ru : en;
  const std::string_view found = index.at(static_cast<std::size_t>(key));
  // A key missing from a catalogue (the catalogue test forbids it) falls back to English.
  return found.empty() ? en.at(static_cast<std::size_t>(key)) : found;
}

Message Message::verbatim(std::string sentence) { return Message(Text::verbatim, std::move(sentence)); }

std::string Message::text(Language language) const {
  fmt::dynamic_format_arg_store<fmt::format_context> args;
  for (const Value& v : values) {
    if (const Text* key = std::get_if<Text>(&v)) {
      args.push_back(std::string(foglab::text(language, *key)));
    } else {
      std::visit([&](const auto& x) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(x)>, Text>) args.push_back(x);
      }, v);
    }
  }
  return fmt::vformat(foglab::text(language, key), args);
}

std::vector<std::string> english(const std::vector<Message>& messages) {
  std::vector<std::string> out;
  out.reserve(messages.size());
  for (const Message& m : messages) out.push_back(m.text());
  return out;
}

}  // namespace foglab
