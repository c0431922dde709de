// foglab — the channel-naming rules (channels.h).
#include "foglab/io/channels.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "foglab/core/text.h"

namespace foglab::io {

bool is_time_channel_name(std::string_view name, NameMatch match) {
  const bool ignore_case = match == NameMatch::ignore_case;
  if (ignore_case && name == "T") return false;  // the lab's temperature, not time
  const std::string key = ignore_case ? ascii_lower(name) : std::string(name);
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
  const std::string key = ascii_lower(name);
  for (const auto& c : channels) {
    // (any case of t, time, time_s: a time column is no temperature)
    if (ascii_lower(c) == key && !is_time_channel_name(key, NameMatch::exact)) return c;
  }
  return std::nullopt;
}

std::optional<Sensor> sensor_by_name(std::string_view name) {
  const std::string n = ascii_lower(name);
  // The name's first word: "gyro_x_dps" -> "gyro", "ax" -> "ax".
  const std::string head = n.substr(0, std::min(n.find_first_of("_.- "), n.size()));
  auto axis_named = [&](char sensor) {
    // g, gx, g_x, gyr..: a sensor letter, then an axis letter or nothing.
    if (head.empty() || head[0] != sensor) return false;
    if (head.size() == 1) {
      const std::size_t rest = head.size() + 1;
      return n.size() > rest && std::string_view("xyz").find(n[rest]) != std::string::npos &&
             (n.size() == rest + 1 || !std::isalpha(static_cast<unsigned char>(n[rest + 1])));
    }
    return head.size() == 2 && std::string_view("xyz").find(head[1]) != std::string::npos;
  };
  if (n.find("gyr") != std::string::npos || n.find("omega") != std::string::npos ||
      n.find("angular") != std::string::npos || axis_named('g') || axis_named('w')) {
    return Sensor::gyroscope;
  }
  if (n.find("acc") != std::string::npos || n.find("linear") != std::string::npos ||
      axis_named('a')) {
    return Sensor::accelerometer;
  }
  return std::nullopt;
}

std::vector<std::string> inertial_channels(const std::vector<std::string>& channels) {
  std::vector<std::string> out;
  for (const std::string& c : channels) {
    if (sensor_by_name(c)) out.push_back(c);
  }
  return out;
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
