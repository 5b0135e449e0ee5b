// A stand-in benchmark suite for the runner's test. Behaviour follows its file name (the test
// links it as slide-bench-<name>): "failing" writes its figures then exits 3, "nojson" writes
// nothing, "badjson" writes a broken file, anything else writes two figures and exits 0.
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  std::string json;
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--json") == 0) json = argv[i + 1];
  const std::string self = argv[0];
  const std::string name = self.substr(self.rfind("slide-bench-") == std::string::npos ? 0 : self.rfind("slide-bench-") + 12);
  std::cout << "fake suite " << name << "\n";
  if (name == "nojson") return 0;
  if (json.empty()) {
    std::cerr << "no --json given\n";
    return 2;
  }
  std::ofstream out(json);
  if (name == "badjson") {
    out << "{\"suite\": \"badjson\", \"results\": [ {\"name\": 1 ";
    return 0;
  }
  out << "{\"suite\": \"" << name << "\", \"results\": [\n"
      << "  {\"name\": \"" << name << ".ate_m\", \"value\": 0.5, \"unit\": \"m\", \"target\": 1.0, \"paper\": 0.54, "
      << "\"better\": \"lower\"},\n"
      << "  {\"name\": \"" << name << ".f1\", \"value\": 0.7, \"unit\": \"\", \"target\": 0.8, \"better\": \"higher\", "
      << "\"note\": \"3 runs\"}\n]}\n";
  return name == "failing" ? 3 : 0;
}
