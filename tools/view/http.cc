#include "view/http.h"

#include <sys/stat.h>

#include <cctype>
#include <filesystem>

#include "io/result_io.h"

namespace vb::view {

namespace {

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string Trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t')) --e;
  return s.substr(b, e - b);
}

const char* StatusText(int status) {
  switch (status) {
    case 200: return "OK";
    case 302: return "Found";
    case 400: return "Bad Request";
    case 403: return "Forbidden";
    case 404: return "Not Found";
    case 405: return "Method Not Allowed";
    case 409: return "Conflict";
    case 413: return "Payload Too Large";
    case 422: return "Unprocessable Entity";
    case 500: return "Internal Server Error";
    default: return "Status";
  }
}

}  // namespace

bool UrlDecode(const std::string& text, bool plus_is_space, std::string* out) {
  out->clear();
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '%') {
      if (i + 2 >= text.size()) return false;
      const int hi = HexValue(text[i + 1]);
      const int lo = HexValue(text[i + 2]);
      if (hi < 0 || lo < 0) return false;
      out->push_back(static_cast<char>(hi * 16 + lo));
      i += 2;
    } else if (c == '+' && plus_is_space) {
      out->push_back(' ');
    } else {
      out->push_back(c);
    }
  }
  return true;
}

HttpParse ParseHttpRequest(const std::string& data, HttpRequest* request, std::string* error) {
  const size_t end = data.find("\r\n\r\n");
  if (end == std::string::npos) {
    if (data.size() > kMaxRequestHeadBytes) {
      *error = "request head longer than " + std::to_string(kMaxRequestHeadBytes) + " bytes";
      return HttpParse::kBad;
    }
    return HttpParse::kIncomplete;
  }
  if (end > kMaxRequestHeadBytes) {
    *error = "request head longer than " + std::to_string(kMaxRequestHeadBytes) + " bytes";
    return HttpParse::kBad;
  }
  *request = HttpRequest();
  size_t line_end = data.find("\r\n");
  const std::string line = data.substr(0, line_end);
  const size_t sp1 = line.find(' ');
  const size_t sp2 = sp1 == std::string::npos ? std::string::npos : line.find(' ', sp1 + 1);
  const bool version_ok = sp2 != std::string::npos &&
                          (line.compare(sp2 + 1, std::string::npos, "HTTP/1.1") == 0 ||
                           line.compare(sp2 + 1, std::string::npos, "HTTP/1.0") == 0);
  if (sp1 == std::string::npos || !version_ok) {
    *error = "malformed request line '" + line + "'";
    return HttpParse::kBad;
  }
  request->method = line.substr(0, sp1);
  const std::string target = line.substr(sp1 + 1, sp2 - sp1 - 1);
  if (target.empty() || target[0] != '/') {
    *error = "request target must be an absolute path, got '" + target + "'";
    return HttpParse::kBad;
  }
  const size_t q = target.find('?');
  if (!UrlDecode(target.substr(0, q), false, &request->path)) {
    *error = "malformed percent escape in '" + target + "'";
    return HttpParse::kBad;
  }
  if (q != std::string::npos) {
    const std::string query = target.substr(q + 1);
    size_t start = 0;
    while (start <= query.size()) {
      size_t amp = query.find('&', start);
      if (amp == std::string::npos) amp = query.size();
      const std::string item = query.substr(start, amp - start);
      if (!item.empty()) {
        const size_t eq = item.find('=');
        std::string key, value;
        if (!UrlDecode(item.substr(0, eq), true, &key) ||
            !UrlDecode(eq == std::string::npos ? "" : item.substr(eq + 1), true, &value)) {
          *error = "malformed percent escape in query '" + item + "'";
          return HttpParse::kBad;
        }
        request->query[key] = value;
      }
      start = amp + 1;
    }
  }
  while (line_end < end) {
    const size_t next = data.find("\r\n", line_end + 2);
    const std::string header = data.substr(line_end + 2, next - line_end - 2);
    line_end = next;
    if (header.empty()) continue;
    const size_t colon = header.find(':');
    if (colon == std::string::npos || colon == 0) {
      *error = "malformed header line '" + header + "'";
      return HttpParse::kBad;
    }
    request->headers[Lower(header.substr(0, colon))] = Trim(header.substr(colon + 1));
  }
  return HttpParse::kRequest;
}

namespace {

// host[:port] is a loopback name of this server.
bool IsLocalHost(const std::string& host_port, int port) {
  std::string host = host_port, port_text;
  const size_t colon = host_port.rfind(':');
  if (colon != std::string::npos && host_port.find(']', colon) == std::string::npos) {
    host = host_port.substr(0, colon);
    port_text = host_port.substr(colon + 1);
  }
  host = Lower(host);
  if (host != "localhost" && host != "127.0.0.1" && host != "[::1]") return false;
  if (port_text.empty()) return port == 80;
  return port_text == std::to_string(port);
}

}  // namespace

std::string HostOriginProblem(const HttpRequest& request, int port) {
  const std::string allowed = "vb_view answers only requests for localhost, 127.0.0.1 or [::1] "
                              "on port " + std::to_string(port);
  const auto host = request.headers.find("host");
  if (host == request.headers.end()) return "the request has no Host header; " + allowed;
  if (!IsLocalHost(host->second, port)) {
    return "Host '" + host->second + "' is not this server; " + allowed;
  }
  const auto origin = request.headers.find("origin");
  if (origin != request.headers.end()) {
    const std::string o = origin->second;
    const std::string scheme = "http://";
    if (o.compare(0, scheme.size(), scheme) != 0 || !IsLocalHost(o.substr(scheme.size()), port)) {
      return "Origin '" + o + "' is not this server's page; " + allowed;
    }
  }
  return "";
}

ServedFile ResolveServedFile(const std::string& root, const std::string& path,
                             uint64_t max_bytes) {
  namespace fs = std::filesystem;
  ServedFile f;
  const auto refuse = [&](int status, const std::string& why) {
    f.status = status;
    f.problem = why;
    return f;
  };
  std::error_code ec;
  const fs::path real_root = fs::canonical(root, ec);
  if (ec) return refuse(404, "does not exist (the served directory cannot be resolved)");
  const fs::path real = fs::canonical(path, ec);
  if (ec) return refuse(404, "does not exist");
  const std::string r = real_root.string(), p = real.string();
  const bool inside = r == "/" || (p.compare(0, r.size(), r) == 0 && p.size() > r.size() &&
                                   p[r.size()] == '/');
  if (!inside) return refuse(403, "resolves outside the served directory (a symbolic link out of it)");
  struct stat st {};
  if (::stat(p.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return refuse(404, "does not exist");
  if (static_cast<uint64_t>(st.st_size) > max_bytes) {
    return refuse(413, "is " + std::to_string(st.st_size) + " bytes, more than the " +
                           std::to_string(max_bytes) + " bytes vb_view serves");
  }
  f.resolved = p;
  return f;
}

std::string SafeRelativePath(const std::string& url_path, const std::string& prefix) {
  if (url_path.compare(0, prefix.size(), prefix) != 0) return "";
  const std::string rel = url_path.substr(prefix.size());
  if (rel.empty()) return "";
  size_t start = 0;
  while (start <= rel.size()) {
    size_t slash = rel.find('/', start);
    if (slash == std::string::npos) slash = rel.size();
    const std::string segment = rel.substr(start, slash - start);
    if (segment.empty() || segment == "." || segment == "..") return "";
    start = slash + 1;
  }
  for (char c : rel) {
    if (c == '\0' || c == '\\') return "";
  }
  return rel;
}

std::string ContentType(const std::string& path) {
  const size_t dot = path.rfind('.');
  const std::string ext = dot == std::string::npos ? "" : Lower(path.substr(dot + 1));
  if (ext == "html") return "text/html; charset=utf-8";
  if (ext == "js" || ext == "mjs") return "text/javascript; charset=utf-8";
  if (ext == "css") return "text/css; charset=utf-8";
  if (ext == "json") return "application/json; charset=utf-8";
  if (ext == "csv" || ext == "yaml" || ext == "md" || ext == "txt") {
    return "text/plain; charset=utf-8";
  }
  if (ext == "png") return "image/png";
  if (ext == "svg") return "image/svg+xml";
  return "application/octet-stream";
}

std::string HttpResponse(int status, const std::string& content_type, const std::string& body,
                         int cache_seconds) {
  std::string out = "HTTP/1.1 " + std::to_string(status) + " " + StatusText(status) + "\r\n";
  out += "Content-Type: " + content_type + "\r\n";
  out += "Content-Length: " + std::to_string(body.size()) + "\r\n";
  out += cache_seconds > 0 ? "Cache-Control: max-age=" + std::to_string(cache_seconds) + "\r\n"
                           : std::string("Cache-Control: no-store\r\n");
  out += "Connection: close\r\n\r\n";
  return out + body;
}

std::string HttpJsonError(int status, const std::string& message) {
  return HttpResponse(status, "application/json; charset=utf-8",
                      "{\"error\": " + io::JsonString(message) + "}\n");
}

}  // namespace vb::view
