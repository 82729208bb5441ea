// The executables' entry point (cpp/apps/common/app.hpp) at its last resort: out of memory
// inside an OpenMP region, where no handler of run_app can catch it (the exception reaches
// std::terminate), still ends in exit 1 with one line, and the run's outputs are undone: the
// files it wrote are removed and an earlier run's file it replaced is back.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <new>
#include <sstream>
#include <string>

#include "common/app.hpp"
#include "softsim/io/atomic_file.hpp"

using namespace softsim;

namespace {

[[gnu::noinline]] void allocation_fails() { throw std::bad_alloc(); }

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int run_failing_in_parallel(const std::string& earlier, const std::string& fresh) {
  app::AppInfo info;
  info.name = "entry_test";
  info.needs_config = false;
  info.needs_out = false;
  char name[] = "entry_test";
  char* argv[] = {name, nullptr};
  return app::run_app(1, argv, info, [&](app::AppContext&) {
    io::write_file_atomic(earlier, std::string("this run's"));
    io::write_file_atomic(fresh, std::string("this run's"));
    int sum = 0;
#pragma omp parallel num_threads(2) reduction(+ : sum)
    {
      allocation_fails();
      sum += 1;
    }
    std::printf("%d\n", sum);
  });
}

}  // namespace

TEST(AppEntryDeathTest, OutOfMemoryInAParallelRegionIsExitOneWithOneLineAndUndoesTheOutputs) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "softsim_app_entry_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string earlier = (dir / "series.pvd").string(), fresh = (dir / "snapshot_0.vtu").string();
  std::ofstream(earlier) << "an earlier run's";
  EXPECT_EXIT(run_failing_in_parallel(earlier, fresh), testing::ExitedWithCode(1),
              "^entry_test: internal error: out of memory[^\n]*\n$");
  EXPECT_EQ(read(earlier), "an earlier run's");
  EXPECT_FALSE(std::filesystem::exists(fresh));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
  std::filesystem::remove_all(dir);
}

TEST(AppEntry, AFinishedRunDropsTheEarlierFilesItKeptAside) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "softsim_app_entry_commit";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string earlier = (dir / "series.pvd").string();
  std::ofstream(earlier) << "an earlier run's";
  app::AppInfo info;
  info.name = "entry_test";
  info.needs_config = false;
  info.needs_out = false;
  char name[] = "entry_test";
  char* argv[] = {name, nullptr};
  EXPECT_EQ(app::run_app(1, argv, info, [&](app::AppContext&) { io::write_file_atomic(earlier, std::string("new")); }), 0);
  EXPECT_EQ(read(earlier), "new");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
  std::filesystem::remove_all(dir);
}
