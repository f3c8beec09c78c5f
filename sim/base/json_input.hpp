// The one parser of every JSON input of tessim (configuration files, statistics for `report` and
// `compare`, coverage files): strict, so that a file means one thing.
#pragma once

#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/base/error.hpp"

namespace tessim::sim {

namespace json_input_detail {

// nlohmann's message after its "[json.exception.parse_error.101] " prefix.
inline std::string without_prefix(const std::string& what) {
  if (what.rfind("[json.exception.", 0) == 0)
    if (const std::size_t close = what.find("] "); close != std::string::npos) return what.substr(close + 2);
  return what;
}

// Where the parser is: one frame per open object or array, for the duplicate-key check and for
// naming the element of a message by its path ("int.blocks.1.busy").
struct Frame {
  bool array = false;
  std::size_t index = 0;      // array: the element being read
  std::string key;            // object: the key being read
  std::set<std::string> keys;  // object: the keys read so far
};

inline std::string path_of(const std::vector<Frame>& frames) {
  std::string path;
  for (const Frame& f : frames) {
    const std::string part = f.array ? std::to_string(f.index) : f.key;
    if (part.empty() && !f.array) break;
    path += (path.empty() ? "" : ".") + part;
  }
  return path;
}

}  // namespace json_input_detail

// Parses `text` as exactly one JSON document. Refused as InputError(source, element, reason),
// with nlohmann's text without its "[json.exception...]" prefix:
//  - malformed JSON or anything after the document, a NUL byte included (nlohmann alone would
//    stop reading at a NUL and accept what came before);
//  - an object with the same key twice (nlohmann alone keeps the last; the element names the
//    key's path, "config.tess_factor");
//  - a number beyond the range of a double ("1e400", named by its key's path).
inline nlohmann::json parse_json_text(std::string_view text, const std::string& source) {
  if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos)
    throw InputError(source, "JSON", "byte " + std::to_string(nul + 1) +
                                         " is a NUL byte: a JSON file is text, and nothing may follow the document");
  using json = nlohmann::json;
  using namespace json_input_detail;
  std::vector<Frame> frames;
  auto value_done = [&frames] {
    if (!frames.empty() && frames.back().array) ++frames.back().index;
  };
  const json::parser_callback_t track = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: frames.push_back(Frame{}); break;
      case json::parse_event_t::array_start: frames.push_back(Frame{.array = true, .index = 0, .key = {}, .keys = {}}); break;
      case json::parse_event_t::key: {
        Frame& f = frames.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second)
          throw InputError(source, path_of(frames),
                           "the key appears twice in one object (which of its values is meant is ambiguous)");
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames.pop_back();
        value_done();
        break;
      case json::parse_event_t::value: value_done(); break;
    }
    return true;
  };
  try {
    return json::parse(text.begin(), text.end(), track);
  } catch (const json::out_of_range& e) {
    const std::string path = path_of(frames);
    throw InputError(source, path.empty() ? std::string("JSON") : path,
                     without_prefix(e.what()) + " (beyond the range of a double)");
  } catch (const json::parse_error& e) {
    std::string reason = without_prefix(e.what());
    if (reason.rfind("parse error at ", 0) == 0) reason = reason.substr(15);
    throw InputError(source, "JSON", reason);
  } catch (const json::exception& e) {
    throw InputError(source, "JSON", without_prefix(e.what()));
  }
}

}  // namespace tessim::sim
