// Helpers shared by the libFuzzer targets in tests/fuzz/ (fuzz_obj, fuzz_scene_json, fuzz_image).
//
// The rule every target follows: rc::scene::Error (and, from the golden model, std::runtime_error)
// thrown for bad input is a correct outcome. Any other exception is a finding: fuzz_fail() prints
// its type and message and aborts, so libFuzzer records the input as a crash. A broken invariant
// in a result the library returned (a mesh whose triangles index past its vertices, a compiled
// image that its own validator rejects, ...) is reported the same way, and so is an Error whose
// message says "internal error" (the library's own consistency checks failing).
//
// Each process gets one private temporary directory (TMPDIR or /tmp, removed at exit) for the
// files a target has to write (the MTL part of fuzz_obj's input) or point at (fuzz_scene_json's
// empty base directory).
#pragma once

#include <dirent.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

namespace rc::fuzz {

[[noreturn]] inline void fuzz_fail(const std::string& what) {
  std::fprintf(stderr, "\n==FUZZ FINDING== %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

// The message for an exception of an unexpected type (called inside a catch block).
inline std::string describe_current_exception() {
  try {
    throw;
  } catch (const std::exception& e) {
    return std::string("unexpected exception of type ") + typeid(e).name() + ": " + e.what();
  } catch (...) {
    return "unexpected exception of a non-std type";
  }
}

// An rc::scene::Error is a correct outcome unless it reports a bug of the library: the library's
// consistency checks throw "internal error: ..." or "FILE: internal error: ..." (messages that
// quote the input can hold those words too, but after a blank or a quote).
inline void check_error_message(const char* what) {
  const std::string m(what);
  const size_t at = m.find("internal error: ");
  if (at == std::string::npos) return;
  const std::string prefix = m.substr(0, at);
  const bool own =
      prefix.empty() || (prefix.size() >= 2 && prefix.compare(prefix.size() - 2, 2, ": ") == 0 &&
                         prefix.find_first_of(" '\"\n", 0) == prefix.size() - 1);
  if (own) fuzz_fail("the library reports an internal error: " + m);
}

// Removes the directory's files (one level: the targets create no subdirectories) and the
// directory.
inline void remove_tree(const std::string& dir) {
  if (DIR* d = opendir(dir.c_str())) {
    while (const dirent* e = readdir(d)) {
      const std::string n = e->d_name;
      if (n != "." && n != "..") unlink((dir + "/" + n).c_str());
    }
    closedir(d);
  }
  rmdir(dir.c_str());
}

// This process's temporary directory, created on first use.
inline const std::string& temp_dir(const char* tag) {
  static const std::string dir = [tag] {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/rcfuzz-" + tag + "-XXXXXX";
    if (!mkdtemp(pattern.data())) fuzz_fail("cannot create a temporary directory " + pattern);
    static std::string* keep = new std::string(pattern);  // for the atexit handler
    std::atexit([] { remove_tree(*keep); });
    return pattern;
  }();
  return dir;
}

}  // namespace rc::fuzz
