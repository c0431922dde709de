// foglab — the channel-naming rules (channels.h).
#include "foglab/io/channels.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

namespace foglab::io {
namespace {

std::string lower_case(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

}  // namespace

bool is_time_channel_name(std::string_view name, NameMatch match) {
  const bool ignore_case = match == NameMatch::ignore_case;
  if (ignore_case && name == "T") return false;  // the lab's temperature, not time
  const std::string key = ignore_case ? lower_case(name) : std::string(name);
  return std::find(kTimeChannelNames.begin(), kTimeChannelNames.end(), key) !=
         kTimeChannelNames.end();
}

bool is_lab_temperature_name(std::string_view name) {
  if (name.empty() || name[0] != 'T') return false;
  return std::all_of(name.begin() + 1, name.end(),
                     [](unsigned char c) { return std::isdigit(c) != 0; });
}

std::vector<std::string> paired_temperature_names(std::string_view rate_channel) {
  std::size_t digits = rate_channel.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(rate_channel[digits - 1])) != 0) {
    --digits;
  }
  if (digits < rate_channel.size() && digits > 0) {
    std::string name = "T";
    name.append(rate_channel.substr(digits));
    return {name};
  }
  if (digits == rate_channel.size()) return {"T", "temperature"};
  return {};  // a bare column index such as "2": nothing to pair by name
}

std::optional<std::string> find_channel(const std::vector<std::string>& channels,
                                        std::string_view name, NameMatch match) {
  for (const auto& c : channels) {
    if (c == name) return c;
  }
  if (match == NameMatch::exact) return std::nullopt;
  const std::string key = lower_case(name);
  for (const auto& c : channels) {
    // (any case of t, time, time_s: a time column is no temperature)
    if (lower_case(c) == key && !is_time_channel_name(key, NameMatch::exact)) return c;
  }
  return std::nullopt;
}

std::string list_names(const std::vector<std::string>& names) {
  auto cut = [](const std::string& name) {
    return name.size() <= 40 ? name : name.substr(0, 37) + "...";
  };
  std::string out;
  const bool all = names.size() <= kListedNames;
  const std::size_t head = all ? names.size() : kListedNames - 2;
  for (std::size_t k = 0; k < head; ++k) out += (k > 0 ? ", " : "") + cut(names[k]);
  if (!all) out += fmt::format(", ..., {} ({} in all)", cut(names.back()), names.size());
  return out;
}

}  // namespace foglab::io
