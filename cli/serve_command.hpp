#pragma once
// `motus serve --plugin FILE.so`: the student's side of `motus grade`. It runs inside the
// sandbox, reads one request per line on standard input and answers each with one line of
// raw outputs (grade/motus/grade/wire.hpp). It never sees an expected value.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace motus::cli {

struct ServeOptions {
  std::vector<std::string> plugins;
};

CLI::App* add_serve_command(CLI::App& app, ServeOptions& options);
int serve_command(const ServeOptions& options);

}  // namespace motus::cli
