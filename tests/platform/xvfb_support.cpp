// Xvfb server, xdotool input, xwd capture and the XWD parser (see xvfb_support.hpp).
#include "platform/xvfb_support.hpp"

#include "lantern/platform/window.hpp"

#define GLFW_EXPOSE_NATIVE_X11
#include <GLFW/glfw3.h>
#include <GLFW/glfw3native.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

extern char** environ;

namespace lantern::test {

namespace {

using Clock = std::chrono::steady_clock;

// A tool that does not answer within this is killed (a hung X call must fail the test).
constexpr auto tool_timeout = std::chrono::seconds(120);
constexpr auto xvfb_start_timeout = std::chrono::seconds(120);

std::vector<char*> c_argv(const std::vector<std::string>& argv) {
    std::vector<char*> out;
    for (const std::string& arg : argv) out.push_back(const_cast<char*>(arg.c_str()));
    out.push_back(nullptr);
    return out;
}

bool on_path(const std::string& tool) {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "");
    for (std::string dir; std::getline(dirs, dir, ':');) {
        if (!dir.empty() && ::access((dir + "/" + tool).c_str(), X_OK) == 0) return true;
    }
    return false;
}

std::string read_text_file(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// Reads what `fds` deliver (-1: none) until each reaches end of file; false when the
// deadline passes first.
bool drain(std::array<int, 2> fds, std::array<std::string*, 2> outs, Clock::time_point deadline) {
    std::array<bool, 2> open = {fds[0] >= 0, fds[1] >= 0};
    char buffer[65536];
    while (open[0] || open[1]) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
        if (left.count() <= 0) return false;
        std::array<pollfd, 2> polls{};
        for (int i = 0; i < 2; ++i) polls[i] = {open[i] ? fds[i] : -1, POLLIN, 0};
        if (::poll(polls.data(), 2, static_cast<int>(left.count())) < 0 && errno != EINTR)
            return false;
        for (int i = 0; i < 2; ++i) {
            if (!open[i] || !(polls[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            const ssize_t n = ::read(fds[i], buffer, sizeof(buffer));
            if (n > 0)
                outs[i]->append(buffer, static_cast<std::size_t>(n));
            else if (n == 0 || errno != EINTR)
                open[i] = false;
        }
    }
    return true;
}

// --- Xvfb --------------------------------------------------------------------------------------

class XvfbServer {
  public:
    XvfbServer() { start(); }
    XvfbServer(const XvfbServer&) = delete;
    XvfbServer& operator=(const XvfbServer&) = delete;
    ~XvfbServer() {
        if (pid_ > 0) {
            ::kill(pid_, SIGTERM);
            int status = 0;
            ::waitpid(pid_, &status, 0);
        }
        if (!log_path_.empty()) std::remove(log_path_.c_str());
    }

    const std::string& display() const { return display_; }
    const std::string& error() const { return error_; }

  private:
    void start();
    bool read_display_number(int fd);
    void fail(const std::string& why) {
        error_ = why;
        const std::string log = read_text_file(log_path_);
        if (!log.empty()) error_ += "; Xvfb said: " + log.substr(0, 2000);
    }

    pid_t pid_ = -1;
    std::string display_;
    std::string error_;
    std::string log_path_;
};

void XvfbServer::start() {
    if (!on_path("Xvfb")) {
        error_ = "Xvfb is not installed (apt-get install xvfb, or run scripts/setup.sh)";
        return;
    }
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
        error_ = std::string("pipe2: ") + std::strerror(errno);
        return;
    }
    // Xvfb writes its display number to fd 3 once it accepts connections (-displayfd).
    constexpr int child_fd = 3;
    log_path_ = "/tmp/lantern-xvfb-" + std::to_string(::getpid()) + ".log";
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[1], child_fd);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    const std::vector<std::string> argv = {"Xvfb",      "-displayfd", std::to_string(child_fd),
                                           "-screen",   "0",          "1280x720x24",
                                           "-nolisten", "tcp",        "-noreset"};
    auto args = c_argv(argv);
    const int spawned = ::posix_spawnp(&pid_, "Xvfb", &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[1]);
    if (spawned != 0) {
        pid_ = -1;
        ::close(fds[0]);
        error_ = std::string("cannot start Xvfb: ") + std::strerror(spawned);
        return;
    }
    const bool ready = read_display_number(fds[0]);
    ::close(fds[0]);
    if (!ready) return;
    ::setenv("DISPLAY", display_.c_str(), 1); // for this process (GLFW) and children (xdotool, xwd)
}

bool XvfbServer::read_display_number(int fd) {
    std::string number, ignored;
    const int no_fd = -1;
    if (!drain({fd, no_fd}, {&number, &ignored}, Clock::now() + xvfb_start_timeout) ||
        number.empty()) {
        fail(number.empty() ? "Xvfb exited without reporting a display"
                            : "Xvfb did not start in time");
        return false;
    }
    while (!number.empty() && (number.back() == '\n' || number.back() == '\r')) number.pop_back();
    display_ = ":" + number;
    return true;
}

XvfbServer& shared_server() {
    static XvfbServer server; // stopped at exit, after every test
    return server;
}

std::string window_arg(std::uint64_t window) {
    return std::to_string(window);
}

// --- XWD ---------------------------------------------------------------------------------------

// The fields of XWDFileHeader (X11/XWDFile.h): 25 big-endian 32-bit words.
struct XwdHeader {
    std::uint32_t header_size, file_version, pixmap_format, pixmap_depth, pixmap_width,
        pixmap_height, xoffset, byte_order, bitmap_unit, bitmap_bit_order, bitmap_pad,
        bits_per_pixel, bytes_per_line, visual_class, red_mask, green_mask, blue_mask, bits_per_rgb,
        colormap_entries, ncolors, window_width, window_height, window_x, window_y, window_bdrwidth;
};
constexpr std::size_t xwd_header_bytes = 100;
constexpr std::size_t xwd_color_bytes = 12;
constexpr std::uint32_t xwd_z_pixmap = 2;
constexpr std::uint32_t xwd_true_color = 4, xwd_direct_color = 5;
constexpr std::uint32_t xwd_max_side = 32768;

std::uint32_t read_be32(const std::uint8_t* p) {
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
           p[3];
}

XwdHeader read_header(const std::uint8_t* p) {
    std::array<std::uint32_t, 25> w{};
    for (std::size_t i = 0; i < w.size(); ++i) w[i] = read_be32(p + 4 * i);
    return {w[0],  w[1],  w[2],  w[3],  w[4],  w[5],  w[6],  w[7],  w[8],
            w[9],  w[10], w[11], w[12], w[13], w[14], w[15], w[16], w[17],
            w[18], w[19], w[20], w[21], w[22], w[23], w[24]};
}

// One channel of a pixel value: masked, shifted down, scaled to 8 bits.
std::uint8_t channel(std::uint32_t pixel, std::uint32_t mask) {
    if (mask == 0) return 0;
    const int shift = __builtin_ctz(mask);
    const std::uint32_t max = mask >> shift;
    const std::uint32_t value = (pixel & mask) >> shift;
    return static_cast<std::uint8_t>((value * 255 + max / 2) / max);
}

Result<void> check_xwd_header(const XwdHeader& h, std::size_t size) {
    if (h.file_version != 7) return make_error("xwd: not an XWD version 7 file");
    if (h.header_size < xwd_header_bytes || h.header_size > size)
        return make_error("xwd: bad header size");
    if (h.pixmap_format != xwd_z_pixmap)
        return make_error("xwd: only ZPixmap images are supported");
    if (h.visual_class != xwd_true_color && h.visual_class != xwd_direct_color)
        return make_error("xwd: only TrueColor and DirectColor visuals are supported");
    if (h.bits_per_pixel != 16 && h.bits_per_pixel != 24 && h.bits_per_pixel != 32)
        return make_error("xwd: unsupported bits per pixel " + std::to_string(h.bits_per_pixel));
    if (h.pixmap_width == 0 || h.pixmap_height == 0 || h.pixmap_width > xwd_max_side ||
        h.pixmap_height > xwd_max_side)
        return make_error("xwd: bad image size");
    if (std::uint64_t{h.bytes_per_line} < std::uint64_t{h.pixmap_width} * (h.bits_per_pixel / 8))
        return make_error("xwd: bytes per line shorter than a row");
    const std::uint64_t data_start =
        std::uint64_t{h.header_size} + std::uint64_t{h.ncolors} * xwd_color_bytes;
    const std::uint64_t data_size = std::uint64_t{h.bytes_per_line} * h.pixmap_height;
    if (data_start + data_size > size) return make_error("xwd: the file is truncated");
    return {};
}

} // namespace

// --- Public ------------------------------------------------------------------------------------

Result<std::string> xvfb_display() {
    const XvfbServer& server = shared_server();
    if (server.display().empty()) return make_error(server.error());
    return server.display();
}

std::string missing_x_tools() {
    std::string missing;
    for (const char* tool : {"xdotool", "xwd"}) {
        if (!on_path(tool)) missing += (missing.empty() ? "" : ", ") + std::string(tool);
    }
    return missing;
}

std::uint64_t x11_window(const platform::Window& window) {
    return static_cast<std::uint64_t>(glfwGetX11Window(window.glfw_handle()));
}

bool poll_until(platform::Window& window, const std::function<bool()>& done,
                std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    do {
        window.poll();
        if (done()) return true;
        ::usleep(2000);
    } while (Clock::now() < deadline);
    return false;
}

Result<std::string> run_tool(const std::vector<std::string>& argv) {
    int out[2], err[2];
    if (::pipe2(out, O_CLOEXEC) != 0 || ::pipe2(err, O_CLOEXEC) != 0)
        return make_error(std::string("pipe2: ") + std::strerror(errno));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out[1], 1);
    posix_spawn_file_actions_adddup2(&actions, err[1], 2);
    auto args = c_argv(argv);
    pid_t pid = -1;
    const int spawned =
        ::posix_spawnp(&pid, argv[0].c_str(), &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(out[1]);
    ::close(err[1]);
    std::string stdout_text, stderr_text;
    const bool finished = spawned == 0 && drain({out[0], err[0]}, {&stdout_text, &stderr_text},
                                                Clock::now() + tool_timeout);
    ::close(out[0]);
    ::close(err[0]);
    if (spawned != 0) return make_error("cannot run " + argv[0] + ": " + std::strerror(spawned));
    if (!finished) ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (!finished) return make_error(argv[0] + " did not finish in time (killed)");
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return make_error(argv[0] + " failed (status " + std::to_string(status) +
                          "): " + stderr_text);
    return stdout_text;
}

Result<void> x_focus(std::uint64_t window) {
    auto r = run_tool({"xdotool", "windowfocus", "--sync", window_arg(window)});
    if (!r) return r.error();
    return {};
}

Result<void> x_key(std::uint64_t window, const std::string& keysym, bool down) {
    auto r = run_tool({"xdotool", "windowfocus", "--sync", window_arg(window),
                       down ? "keydown" : "keyup", keysym});
    if (!r) return r.error();
    return {};
}

Result<void> x_mouse_move(std::uint64_t window, int x, int y) {
    auto r = run_tool({"xdotool", "mousemove", "--window", window_arg(window), "--sync",
                       std::to_string(x), std::to_string(y)});
    if (!r) return r.error();
    return {};
}

Result<void> x_button(int button, bool down) {
    auto r = run_tool({"xdotool", down ? "mousedown" : "mouseup", std::to_string(button)});
    if (!r) return r.error();
    return {};
}

std::uint32_t RgbImage::at(std::uint32_t x, std::uint32_t y) const {
    const std::size_t i = (std::size_t{y} * width + x) * 3;
    return (std::uint32_t{rgb.at(i)} << 16) | (std::uint32_t{rgb.at(i + 1)} << 8) | rgb.at(i + 2);
}

Result<RgbImage> capture_window(std::uint64_t window) {
    auto dump = run_tool({"xwd", "-id", window_arg(window), "-silent"});
    if (!dump) return dump.error();
    return parse_xwd({reinterpret_cast<const std::uint8_t*>(dump->data()), dump->size()});
}

Result<RgbImage> parse_xwd(std::span<const std::uint8_t> bytes) {
    if (bytes.size() < xwd_header_bytes) return make_error("xwd: the file is truncated");
    const XwdHeader h = read_header(bytes.data());
    if (auto ok = check_xwd_header(h, bytes.size()); !ok) return ok.error();
    const std::uint8_t* data =
        bytes.data() + h.header_size + std::size_t{h.ncolors} * xwd_color_bytes;
    const std::uint32_t pixel_bytes = h.bits_per_pixel / 8;
    RgbImage image;
    image.width = h.pixmap_width;
    image.height = h.pixmap_height;
    image.rgb.resize(std::size_t{image.width} * image.height * 3);
    for (std::uint32_t y = 0; y < image.height; ++y) {
        const std::uint8_t* row = data + std::size_t{y} * h.bytes_per_line;
        for (std::uint32_t x = 0; x < image.width; ++x) {
            const std::uint8_t* p = row + std::size_t{x} * pixel_bytes;
            std::uint32_t pixel = 0;
            for (std::uint32_t b = 0; b < pixel_bytes; ++b) {
                const std::uint32_t byte = p[h.byte_order == 0 ? b : pixel_bytes - 1 - b];
                pixel |= byte << (8 * b); // byte_order 0: least significant byte first
            }
            std::uint8_t* out = image.rgb.data() + (std::size_t{y} * image.width + x) * 3;
            out[0] = channel(pixel, h.red_mask);
            out[1] = channel(pixel, h.green_mask);
            out[2] = channel(pixel, h.blue_mask);
        }
    }
    return image;
}

} // namespace lantern::test
