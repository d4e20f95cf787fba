#include "lantern/core/machine.hpp"

#include <cstdio>
#include <fstream>
#include <string>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/utsname.h>
#include <thread>
#include <unistd.h>

namespace lantern {

MachineInfo machine_info() {
    MachineInfo info;
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);) {
        if (line.rfind("model name", 0) == 0) {
            auto colon = line.find(':');
            if (colon != std::string::npos) info.cpu_model = line.substr(colon + 2);
            break;
        }
    }
    if (info.cpu_model.empty()) info.cpu_model = "unknown CPU";
    info.logical_cores = std::thread::hardware_concurrency();
    long pages = sysconf(_SC_PHYS_PAGES);
    long page_size = sysconf(_SC_PAGE_SIZE);
    if (pages > 0 && page_size > 0) info.memory_gib = double(pages) * double(page_size) / (1024.0 * 1024.0 * 1024.0);
    utsname uts{};
    if (uname(&uts) == 0) info.kernel = std::string(uts.sysname) + " " + uts.release;
#if defined(__clang__)
    info.compiler = "clang " __clang_version__;
#elif defined(__GNUC__)
    info.compiler = "g++ " __VERSION__;
#endif
#if defined(LANTERN_SANITIZER_BUILD)
    info.build_type = "sanitizer build";
#elif defined(NDEBUG)
    info.build_type = "optimised";
#else
    info.build_type = "debug";
#endif
#if defined(LANTERN_ENABLE_ASSERTS)
    info.build_type += ", asserts on";
#endif
    return info;
}

std::string describe_machine() {
    MachineInfo m = machine_info();
    char buffer[512];
    std::snprintf(buffer, sizeof(buffer), "%s, %u logical cores, %.1f GiB, %s, %s (%s)",
                  m.cpu_model.c_str(), m.logical_cores, m.memory_gib, m.kernel.c_str(),
                  m.compiler.c_str(), m.build_type.c_str());
    return buffer;
}

std::uint64_t resident_set_bytes() {
    std::ifstream statm("/proc/self/statm");
    std::uint64_t size_pages = 0, resident_pages = 0;
    if (!(statm >> size_pages >> resident_pages)) return 0;
    const long page = sysconf(_SC_PAGESIZE);
    return resident_pages * std::uint64_t(page > 0 ? page : 4096);
}

bool lower_thread_priority() {
    // On Linux a priority set for a thread id holds for that thread only.
    return setpriority(PRIO_PROCESS, id_t(syscall(SYS_gettid)), 19) == 0;
}

} // namespace lantern
