#pragma once
// Text outputs of the command line (JSON documents, CSV, traces) and raw byte files, written so
// that a failed write is an error rather than a silently truncated file.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

namespace cli {

// Pretty-printed with a two-space indent and a final newline. Throws OutputError naming the path.
void WriteJson(const std::filesystem::path& path, const nlohmann::ordered_json& json);
// Exactly `text`. Throws OutputError naming the path.
void WriteText(const std::filesystem::path& path, const std::string& text);
// Exactly `bytes`. Throws OutputError naming the path.
void WriteBytes(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

}  // namespace cli
