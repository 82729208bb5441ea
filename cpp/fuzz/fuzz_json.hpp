#pragma once
// The fuzz targets' common first step: the bytes as a JSON document, through the parser every
// executable uses (JsonReader::parse_text: nesting bound, duplicate keys). Text it refuses is
// not a finding; the readers behind it are what is fuzzed.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "softsim/io/errors.hpp"
#include "softsim/io/json_reader.hpp"

inline bool parse_fuzz_json(const std::uint8_t* data, std::size_t size, nlohmann::json& doc) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    doc = softsim::io::JsonReader::parse_text(text, "fuzz.json");
  } catch (const softsim::InputError&) {
    return false;
  }
  return true;
}
