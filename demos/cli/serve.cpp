// `tumble view`: a minimal HTTP/1.0-style server on 127.0.0.1 for the viewer page, its three.js
// modules and one replay file. The browser needs http (ES modules are refused from file://).
// One thread per connection, because a browser opens sockets it may send nothing on for a while;
// every answer closes its connection. Only files under the viewer folder are served, and of its
// node_modules only three.

#include "serve.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <thread>

#include "tumble/core/error.h"
#include "tumble/replay/replay.h"

namespace tumble::cli {
namespace {

namespace fs = std::filesystem;

std::string contentType(const fs::path& path) {
    const std::string ext = path.extension().string();
    if (ext == ".html")
        return "text/html; charset=utf-8";
    if (ext == ".js" || ext == ".mjs")
        return "text/javascript; charset=utf-8";
    if (ext == ".css")
        return "text/css; charset=utf-8";
    if (ext == ".json")
        return "application/json";
    return "application/octet-stream";
}

void sendAll(int socket, const std::string& data) {
    std::size_t sent = 0;
    while (sent < data.size()) {
        const ssize_t n = ::send(socket, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
        if (n <= 0)
            return;
        sent += static_cast<std::size_t>(n);
    }
}

void answer(int socket, const std::string& status, const std::string& type,
            const std::string& body) {
    std::ostringstream head;
    head << "HTTP/1.1 " << status << "\r\nContent-Type: " << type
         << "\r\nContent-Length: " << body.size()
         << "\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n";
    sendAll(socket, head.str() + body);
}

/// The file a request path names, or "" when it names none that may be served.
fs::path resolve(const std::string& target, const ServeOptions& options) {
    std::string path = target.substr(0, target.find_first_of("?#"));
    if (path == "/")
        path = "/index.html";
    if (path == "/replay.tumble")
        return options.replay;
    if (path.find("..") != std::string::npos || path.find('\\') != std::string::npos)
        return {};
    if (path.rfind("/node_modules/", 0) == 0 && path.rfind("/node_modules/three/", 0) != 0)
        return {};
    return fs::path(options.viewerDir) / path.substr(1);
}

void handle(int socket, const ServeOptions& options) {
    std::string request;
    char buffer[4096];
    while (request.find("\r\n\r\n") == std::string::npos && request.size() < 65536) {
        const ssize_t n = ::recv(socket, buffer, sizeof buffer, 0);
        if (n <= 0)
            break;
        request.append(buffer, static_cast<std::size_t>(n));
    }
    std::istringstream line(request);
    std::string method, target;
    line >> method >> target;
    const fs::path file = method == "GET" ? resolve(target, options) : fs::path();
    std::ifstream in(file, std::ios::binary);
    if (file.empty() || !fs::is_regular_file(file) || !in) {
        answer(socket, "404 Not Found", "text/plain", "not found: " + target + "\n");
    } else {
        std::ostringstream body;
        body << in.rdbuf();
        answer(socket, "200 OK", contentType(file), body.str());
    }
    ::close(socket);
}

}  // namespace

std::string viewerDirectory(const std::string& argv0) {
    if (const char* env = std::getenv("TUMBLE_VIEWER_DIR"))
        return env;
    std::error_code ec;
    const fs::path exe = fs::canonical(fs::path(argv0), ec);
    if (!argv0.empty() && !ec) {
        const fs::path installed = exe.parent_path() / ".." / "share" / "tumble" / "viewer";
        if (fs::is_regular_file(installed / "index.html"))
            return installed.string();
    }
    return TUMBLE_SOURCE_VIEWER_DIR;
}

int serveViewer(const ServeOptions& options, std::ostream& out) {
    readReplay(options.replay);  // a damaged file is refused here, not in the browser
    const fs::path three = fs::path(options.viewerDir) / "node_modules" / "three" / "build";
    if (!fs::is_regular_file(fs::path(options.viewerDir) / "index.html") ||
        !fs::is_directory(three))
        fail("the viewer in ", options.viewerDir,
             " is not set up: run scripts/viewer-deps.sh (npm ci in viewer/)");
    const int server = ::socket(AF_INET, SOCK_STREAM, 0);
    const int yes = 1;
    ::setsockopt(server, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(static_cast<std::uint16_t>(options.port));
    socklen_t length = sizeof address;
    if (server < 0 || ::bind(server, reinterpret_cast<sockaddr*>(&address), length) != 0 ||
        ::listen(server, 64) != 0 ||
        ::getsockname(server, reinterpret_cast<sockaddr*>(&address), &length) != 0)
        fail("tumble view: port ", options.port, " on 127.0.0.1 cannot be listened on");
    out << "viewer: http://127.0.0.1:" << ntohs(address.sin_port) << "/ (" << options.replay
        << "; Ctrl-C stops it)" << std::endl;
    for (;;) {
        const int client = ::accept(server, nullptr, nullptr);
        if (client >= 0)
            std::thread(handle, client, options).detach();
    }
}

}  // namespace tumble::cli
