// Replays the fuzz corpus (tests/fuzz/corpus, grown by scripts/fuzz.sh)
// through the loaders in the normal build: every input loads or is
// rejected with an InputError; nothing else may escape.
#include <doctest/doctest.h>

#include <dirent.h>

#include <vector>

#include "../fuzz/fuzz_input.h"
#include "test_util.h"

TEST_CASE("every fuzz corpus input loads or is rejected cleanly") {
    std::string corpus = pt::test::source_path("tests/fuzz/corpus");
    std::string scratch = pt::test::scratch_dir("fuzz_replay");
    DIR* dir = opendir(corpus.c_str());
    REQUIRE(dir);
    int inputs = 0, valid = 0;
    while (dirent* entry = readdir(dir)) {
        std::string name = entry->d_name;
        if (name == "." || name == "..") continue;
        std::string bytes = pt::test::read_file(corpus + "/" + name);
        CAPTURE(name);
        bool loaded = false;
        CHECK_NOTHROW(loaded = pt::fuzz::load_fuzz_input(reinterpret_cast<const uint8_t*>(bytes.data()),
                                                         bytes.size(), scratch));
        valid += loaded;
        ++inputs;
    }
    closedir(dir);
    CHECK(inputs >= 10);
    CHECK(valid >= 3);  // the corpus keeps some valid scenes, so fuzzing starts deep
}
