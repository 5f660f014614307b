// The query page's files (web/: index.html, soiq.js, style.css), embedded in soiqd at build time
// by cmake/embed_files.cmake (target soiq_web_files, web/CMakeLists.txt), so that soiqd --http
// serves `GET /` and `GET /ui/<file>` without a folder beside the program and always the page it
// was built with.
//
// Input: a path relative to web/, as the URL after /ui/ says it ("index.html", "soiq.js"); no
// leading slash, no "..", compared byte for byte (no decoding, no case folding).
// Output: the file's path, its media type (the Content-Type to send, with charset=utf-8 for text)
// and its bytes, all with static storage; nullptr when no such file was embedded.
// Errors: none. Cost: a linear scan of a handful of entries; thread-safe (constant data).
// Caveats: the bytes are the files as they were at the last build; a change in web/ regenerates
// the source and relinks soiqd.
#pragma once

#include <string_view>

namespace soiq::server::http {

struct WebFile {
  std::string_view path;
  std::string_view media_type;
  std::string_view bytes;
};

const WebFile* find_web_file(std::string_view path);

}  // namespace soiq::server::http
