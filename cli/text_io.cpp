// Text outputs (see text_io.h).

#include "cli/text_io.h"

#include <fstream>

#include "cli/output_error.h"

namespace cli {

void WriteJson(const std::filesystem::path& path, const nlohmann::ordered_json& json) {
  std::ofstream file(path);
  file << json.dump(2) << '\n';
  // Buffered write errors (a full disk) only surface at close.
  file.close();
  if (!file) throw OutputError(path.string() + ": cannot write JSON");
}

void WriteText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream file(path);
  file << text;
  file.close();
  if (!file) throw OutputError(path.string() + ": cannot write text");
}

void WriteBytes(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  std::ofstream file(path, std::ios::binary);
  file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  file.close();
  if (!file) throw OutputError(path.string() + ": cannot write");
}

}  // namespace cli
