#include "modalbench/harness/files.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace modalbench {

void make_output_dir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create the folder " + dir + ": " + ec.message());
  if (!std::filesystem::is_directory(dir)) throw std::runtime_error(dir + " exists and is not a folder");
  if (access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error("cannot write into the folder " + dir + ": " + std::strerror(errno));
}

void write_text_file(const std::string& path, const std::string& content) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  const std::size_t n = std::fwrite(content.data(), 1, content.size(), f);
  const int write_errno = errno;
  const bool flushed = std::fflush(f) == 0;
  const int flush_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (n != content.size()) throw std::runtime_error("cannot write " + path + ": " + std::strerror(write_errno));
  if (!flushed || !closed)
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(flushed ? errno : flush_errno));
}

}  // namespace modalbench
