// The HTTP/1.1 subset vb_view serves: GET requests (one per connection, then close), query
// parameters, safe mapping of URL paths onto a directory, and response text. No I/O here; the
// server (view_server.cc) owns the sockets.
#pragma once

#include <cstdint>
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

// Why the request must not be served by the vb_view listening on 127.0.0.1:`port`, or "" if it
// may: its Host must be one of localhost, 127.0.0.1 or [::1] with that port (the port may be left
// out only when it is 80), and an Origin, when the request has one, must be http:// and such a
// host. A page on another site, a DNS-rebinding name, or a browser tab of another local server
// reaches vb_view through the browser and sends its own Host or Origin; vb_view answers it with
// 403 (NEW-10 of the probe at 8ff4def). Checked on every request and WebSocket upgrade.
std::string HostOriginProblem(const HttpRequest& request, int port);

// Percent-decoding ('+' is a space in queries only). False for a malformed escape.
bool UrlDecode(const std::string& text, bool plus_is_space, std::string* out);

// Maps a URL path below `prefix` (e.g. "/files/") onto a relative file path: "" if the path is
// not below the prefix or would leave it ("..", "." segments, empty segments, NUL, backslash).
std::string SafeRelativePath(const std::string& url_path, const std::string& prefix);

// Content type from the file name's extension (text types with charset=utf-8).
std::string ContentType(const std::string& path);

// Whether `path` (below `root`) may be served: after resolving every symbolic link it must still
// lie inside `root` (itself resolved), so a link in a results directory cannot serve /etc/passwd
// (403; W02 of the probe at 8ff4def), and be a regular file (else 404) of at most max_bytes (a
// sparse 64 GiB file must not be read whole: 413; W06).
struct ServedFile {
  int status = 200;       // 200, 403, 404 or 413
  std::string problem;    // why not, when status != 200
  std::string resolved;   // the resolved path, when 200
};
ServedFile ResolveServedFile(const std::string& root, const std::string& path, uint64_t max_bytes);

// A complete response with Content-Length and Connection: close; not cached unless
// `cache_seconds` > 0 (the vendored library: its folder name carries its version).
std::string HttpResponse(int status, const std::string& content_type, const std::string& body,
                         int cache_seconds = 0);
// A JSON error body {"error": message} with the given status.
std::string HttpJsonError(int status, const std::string& message);

}  // namespace vb::view
