// The HTTP/1.1 subset vb_view serves: GET requests (one per connection, then close), query
// parameters, safe mapping of URL paths onto a directory, and response text. No I/O here; the
// server (view_server.cc) owns the sockets.
#pragma once

#include <map>
#include <string>

namespace vb::view {

struct HttpRequest {
  std::string method;                          // "GET"
  std::string path;                            // decoded, without the query: "/viewer/index.html"
  std::map<std::string, std::string> query;    // decoded parameters
  std::map<std::string, std::string> headers;  // names lower-cased
};

enum class HttpParse { kIncomplete, kRequest, kBad };

// Longest request head accepted (request line + headers); more is an error, not a wait.
constexpr size_t kMaxRequestHeadBytes = 16 * 1024;

// Parses the head of a request (everything up to the blank line) at the start of `data`.
// kBad: *error names what is malformed (request line, header line, percent escape, size).
HttpParse ParseHttpRequest(const std::string& data, HttpRequest* request, std::string* error);

// Percent-decoding ('+' is a space in queries only). False for a malformed escape.
bool UrlDecode(const std::string& text, bool plus_is_space, std::string* out);

// Maps a URL path below `prefix` (e.g. "/files/") onto a relative file path: "" if the path is
// not below the prefix or would leave it ("..", "." segments, empty segments, NUL, backslash).
std::string SafeRelativePath(const std::string& url_path, const std::string& prefix);

// Content type from the file name's extension (text types with charset=utf-8).
std::string ContentType(const std::string& path);

// A complete response with Content-Length and Connection: close; not cached unless
// `cache_seconds` > 0 (the vendored library: its folder name carries its version).
std::string HttpResponse(int status, const std::string& content_type, const std::string& body,
                         int cache_seconds = 0);
// A JSON error body {"error": message} with the given status.
std::string HttpJsonError(int status, const std::string& message);

}  // namespace vb::view
