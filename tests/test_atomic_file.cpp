#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include "spectral/atomic_file.hpp"
#include "spectral/input_error.hpp"

using namespace skinspec;
namespace fs = std::filesystem;

namespace {

// An empty scratch folder of this test process.
fs::path fresh_folder(const std::string& name) {
    const auto dir = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

}  // namespace

TEST_CASE("a failed write leaves neither the file nor a temporary, a good one replaces atomically", "[atomic_file]") {
    const auto dir = fs::temp_directory_path() / "skinspec_atomic_test";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const auto file = dir / "out.csv";
    CHECK_THROWS_AS(write_atomically(file,
                                     [](const fs::path& temporary) {
                                         std::ofstream(temporary) << "half";
                                         throw std::runtime_error("disk full");
                                     }),
                    std::runtime_error);
    CHECK(fs::is_empty(dir));
    write_text_file(file, "first\n", false);
    CHECK_THROWS_WITH(write_text_file(file, "second\n", false), Catch::Contains("exists already (use --overwrite"));
    write_text_file(file, "second\n", true);
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    CHECK(line == "second");
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
    fs::remove_all(dir);
}

TEST_CASE("outputs replace only regular files, and only when claimed with overwrite", "[atomic_file]") {
    const auto dir = fs::temp_directory_path() / "skinspec_atomic_claims";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const auto target = dir / "target.txt";
    std::ofstream(target) << "the user's\n";
    // A symbolic link (or device, FIFO, folder) is never replaced, even with overwrite.
    fs::create_symlink(target, dir / "link.json");
    CHECK_THROWS_WITH(write_text_file(dir / "link.json", "{}", true), Catch::Contains("is a symbolic link; only a regular file is replaced"));
    CHECK(fs::is_symlink(dir / "link.json"));
    CHECK_THROWS_WITH(write_text_file(dir, "x", true), Catch::Contains("is a folder"));
    {
        const OutputClaims command;
        const auto out = dir / "out.json";
        OutputClaims::claim(out, false);
        CHECK_THROWS_WITH(OutputClaims::claim(dir / "." / "out.json", true), Catch::Contains("named as two outputs of one command"));
        // A file that appears while the command runs (another run, the user) is kept: the output is created exclusively.
        CHECK_THROWS_WITH(write_atomically(out, [&](const fs::path& temporary) {
                              std::ofstream(temporary) << "ours";
                              std::ofstream(out) << "theirs";
                          }),
                          Catch::Contains("appeared while this command ran"));
        std::string kept;
        std::getline(std::ifstream(out), kept);
        CHECK(kept == "theirs");
        // Claimed with overwrite, it is replaced.
        const auto replaced = dir / "replaced.json";
        std::ofstream(replaced) << "old";
        OutputClaims::claim(replaced, true);
        write_text_file(replaced, "new\n", false);
        std::string line;
        std::getline(std::ifstream(replaced), line);
        CHECK(line == "new");
    }
    CHECK(std::none_of(fs::directory_iterator(dir), fs::directory_iterator(), [](const fs::directory_entry& e) {
        return e.path().filename().string().find(".partial-") != std::string::npos;
    }));
    fs::remove_all(dir);
}

TEST_CASE("a temporary is created exclusively under an unpredictable name, and a replaced one is never published", "[atomic_file]") {
    const auto dir = fresh_folder("skinspec_atomic_link");
    const auto victim = dir / "victim.txt";
    std::ofstream(victim) << "precious\n";
    // The name a run used to write to (stem.partial-PID.ext), planted as a link to another file: never written through.
    const auto out = dir / "out.json";
    fs::create_symlink(victim, dir / ("out.partial-" + std::to_string(::getpid()) + ".json"));
    std::vector<fs::path> names;
    write_atomically(out, [&](const fs::path& temporary) {
        names.push_back(temporary);
        std::ofstream(temporary) << "{}\n";
    });
    CHECK(fs::is_regular_file(fs::symlink_status(out)));
    // Two runs' temporaries differ (six random characters), with a new file's permissions (not mkstemp's 0600).
    const auto second = dir / "second.json";
    write_atomically(second, [&](const fs::path& temporary) { names.push_back(temporary); std::ofstream(temporary) << "{}\n"; });
    REQUIRE(names.size() == 2);
    CHECK(names[0].filename().string().rfind("out.partial-", 0) == 0);
    CHECK(names[0].extension() == ".json");
    CHECK(names[0].stem().string() != "out.partial-" + std::to_string(::getpid()));
    CHECK((fs::status(second).permissions() & fs::perms::owner_read) != fs::perms::none);
    const auto mask = ::umask(0);
    ::umask(mask);
    CHECK((fs::status(second).permissions() & fs::perms::group_read) == ((mask & S_IRGRP) ? fs::perms::none : fs::perms::group_read));
    // A temporary replaced by a link while it is written (another process in the folder): refused, nothing published,
    // the link's target untouched, the planted link left where it is.
    const auto third = dir / "third.json";
    CHECK_THROWS_WITH(write_atomically(third,
                                       [&](const fs::path& temporary) {
                                           std::ofstream(temporary) << "{}\n";
                                           fs::remove(temporary);
                                           fs::create_symlink(victim, temporary);
                                       }),
                      Catch::Contains("was replaced while it was written"));
    CHECK_FALSE(fs::exists(fs::symlink_status(third)));
    // A writer that writes a new file at the temporary's name (as OpenEXR does) publishes it.
    const auto fourth = dir / "fourth.exr";
    write_atomically(fourth, [&](const fs::path& temporary) {
        fs::remove(temporary);
        std::ofstream(temporary) << "new file\n";
    });
    CHECK(fs::is_regular_file(fs::symlink_status(fourth)));
    std::string kept;
    std::getline(std::ifstream(victim), kept);
    CHECK(kept == "precious");
    fs::remove_all(dir);
}

TEST_CASE("a process that must exit at once removes the temporaries it is writing", "[atomic_file]") {
    // What a second stop signal does before _exit (cli/progress.cpp): here called from inside the writer, as the handler
    // would interrupt it. The temporary goes; nothing is published (the write then fails: its file is gone).
    const auto dir = fresh_folder("skinspec_atomic_exit");
    const auto out = dir / "lut.exr";
    CHECK_THROWS(write_atomically(out, [&](const fs::path& temporary) {
        std::ofstream(temporary) << "half";
        remove_temporaries_in_progress();
        CHECK_FALSE(fs::exists(fs::symlink_status(temporary)));
    }));
    CHECK_FALSE(fs::exists(out));
    CHECK(std::none_of(fs::directory_iterator(dir), fs::directory_iterator(), [](const fs::directory_entry&) { return true; }));
    // After a write, nothing of it is tracked: a later call removes nothing of what was published.
    write_atomically(out, [](const fs::path& temporary) { std::ofstream(temporary) << "whole"; });
    remove_temporaries_in_progress();
    CHECK(fs::is_regular_file(out));
    fs::remove_all(dir);
}
