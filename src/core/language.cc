#include "foglab/core/language.h"

#include <fmt/args.h>
#include <fmt/format.h>

#include <array>
#include <cctype>
#include <string>
#include <utility>

#include "catalogue.h"
#include "foglab/core/error.h"
#include "foglab/core/text.h"

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
  const std::string lower = ascii_lower(text);
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

Message range_message(double low, double high) {
  if (fmt::format("{:.3g}", low) == fmt::format("{:.3g}", high)) return Message(Text::one_of, low);
  return Message(Text::range_of, low, high);
}

std::string Message::text(Language language) const {
  if (empty()) return {};
  fmt::dynamic_format_arg_store<fmt::format_context> args;
  for (const Value& v : values) {
    std::visit(
        [&](const auto& x) {
          using V = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<V, Text>) {
            args.push_back(std::string(foglab::text(language, x)));
          } else if constexpr (std::is_same_v<V, Nested>) {
            args.push_back(x.message->text(language));
          } else if constexpr (std::is_same_v<V, NoiseTermSet>) {
            args.push_back(terms_text(x, language));
          } else if constexpr (std::is_same_v<V, List>) {
            std::string joined;
            for (const Message& m : *x.items)
              joined += (joined.empty() ? "" : ", ") + m.text(language);
            args.push_back(joined);
          } else {
            args.push_back(x);
          }
        },
        v);
  }
  std::string sentence = fmt::vformat(foglab::text(language, key), args);
  // fmt writes an infinite number as "inf", a missing one as "nan": English words in a
  // Russian sentence. Each, as a word of its own, becomes the symbol.
  if (language != Language::en) {
    for (const auto& [word, symbol] : {std::pair{"inf", "∞"}, std::pair{"nan", "—"}}) {
      const std::string_view w = word;
      for (std::size_t at = sentence.find(w); at != std::string::npos;
           at = sentence.find(w, at + 1)) {
        const auto letter = [&](std::size_t i) {
          return std::isalpha(static_cast<unsigned char>(sentence[i])) != 0;
        };
        if ((at > 0 && letter(at - 1)) ||
            (at + w.size() < sentence.size() && letter(at + w.size())))
          continue;
        sentence.replace(at, w.size(), symbol);
      }
    }
  }
  return sentence;
}

std::string terms_text(NoiseTermSet terms, Language language) {
  if (language == Language::en) return to_string(terms);
  std::string symbols;
  for (const NoiseTerm t : kNoiseTerms) {
    if (!terms.contains(t)) continue;
    const Text symbol = t == NoiseTerm::white          ? Text::an_sym_n
                        : t == NoiseTerm::flicker      ? Text::an_sym_b
                        : t == NoiseTerm::random_walk  ? Text::an_sym_k
                        : t == NoiseTerm::ramp         ? Text::an_sym_r
                        : t == NoiseTerm::quantisation ? Text::an_sym_q
                                                       : Text::an_sym_gm;
    if (!symbols.empty()) symbols += '+';
    symbols += text(language, symbol);
  }
  return symbols.empty() ? std::string(text(language, Text::an_none)) : symbols;
}

std::vector<std::string> english(const std::vector<Message>& messages) {
  std::vector<std::string> out;
  out.reserve(messages.size());
  for (const Message& m : messages) out.push_back(m.text());
  return out;
}

}  // namespace foglab
