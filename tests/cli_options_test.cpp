// Integer options read decimal: CLI11 alone converts with base 0, so `--width 0064` was octal 52.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/common_options.h"
#include "cli/raster_options.h"

namespace {

// Parses `aasim raster ARGS` with every command option registered as main() does.
cli::RasterCommandOptions ParseRaster(std::vector<std::string> args) {
  CLI::App app;
  cli::RasterCommandOptions options;
  cli::AddRasterCommand(app, options);
  cli::RequireDecimalIntegers(app);
  args.insert(args.begin(), "raster");
  std::reverse(args.begin(), args.end());  // CLI11 takes a vector in reverse order
  app.parse(args);
  return options;
}

TEST(CliOptions, IntegersWithLeadingZerosAreDecimal) {
  EXPECT_EQ(ParseRaster({"--width", "0064"}).width, 64);
  EXPECT_EQ(ParseRaster({"--height", "010"}).height, 10);
  EXPECT_EQ(ParseRaster({"--samples", "08"}).samples, 8);  // not an invalid octal digit
  EXPECT_EQ(ParseRaster({"--width", "+32"}).width, 32);
}

TEST(CliOptions, NonDecimalIntegersAreUsageErrorsNamingTheOption) {
  for (const char* text : {"0x40", "1e2", "64.0", " 64", "", "-", "0b11"}) {
    SCOPED_TRACE(text);
    try {
      ParseRaster({"--width", text});
      ADD_FAILURE() << "accepted";
    } catch (const CLI::ParseError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("--width"), std::string::npos) << message;
    }
  }
}

}  // namespace
