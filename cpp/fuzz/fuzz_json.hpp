#pragma once
// The fuzz targets' common first step: the bytes as a JSON document. Text that is not JSON is
// not a finding (the parser is nlohmann's); the readers behind it are what is fuzzed.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

inline bool parse_fuzz_json(const std::uint8_t* data, std::size_t size, nlohmann::json& doc) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    return false;
  }
  return true;
}
