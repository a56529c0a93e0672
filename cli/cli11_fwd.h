#pragma once
// CLI11's classes by name only. The headers of cli/ declare the functions that register options;
// only the files that register them include CLI11, whose header-only implementation costs about
// 5 s of compile time in every file that includes it (docs/PERFORMANCE.md, "CI time").

namespace CLI {
class App;
class Validator;
}  // namespace CLI
