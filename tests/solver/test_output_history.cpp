// History CSV: rows are on disk after every write (flushed) and read back exactly with the
// project's CSV reader; the SIGINT helper sets a flag on the first Ctrl-C and lets the second kill.
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>

#include "io/csv.hpp"
#include "solver/output/history_csv.hpp"
#include "solver/output/interrupt.hpp"

namespace fs = std::filesystem;
using namespace cushion::solver;

TEST(HistoryCsv, RowsAreFlushedAndReadBackExactly) {
  const fs::path file =
      fs::temp_directory_path() / ("cushion_h6_history_" + std::to_string(::getpid())) / "history.csv";
  HistoryWriter writer(file, {"top.U3_mm", "top.RF3_N"}, {"case: test"});
  const double rows[3][3] = {{0.0, 0.0, 0.0}, {0.1, -0.2, -1.0 / 3.0}, {30.0, -60.0, -1234.56789012345}};
  for (int r = 0; r < 3; ++r) {
    writer.write_row(rows[r][0], std::vector<double>{rows[r][1], rows[r][2]});
    // Still open: what is on disk already holds every row written so far.
    const cushion::CsvTable t = cushion::read_csv(file);
    ASSERT_EQ(t.rows(), static_cast<std::size_t>(r + 1));
    EXPECT_EQ(t.columns, (std::vector<std::string>{"time_s", "top.U3_mm", "top.RF3_N"}));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(t.data[c][r], rows[r][c]);  // exact round trip
  }
  EXPECT_THROW(writer.write_row(1.0, std::vector<double>{1.0}), std::invalid_argument);
  fs::remove_all(file.parent_path());
}

TEST(Interrupt, FirstCtrlCSetsFlagSecondKills) {
  {
    InterruptGuard guard;
    EXPECT_FALSE(interrupt_requested());
    std::raise(SIGINT);
    EXPECT_TRUE(interrupt_requested());
  }
  clear_interrupt();
  EXPECT_FALSE(interrupt_requested());
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        InterruptGuard guard;
        std::raise(SIGINT);
        if (!interrupt_requested()) std::_Exit(3);
        std::raise(SIGINT);  // default action now: the process ends by SIGINT
        std::_Exit(4);
      },
      testing::KilledBySignal(SIGINT), "interrupt received");
  EXPECT_NE(std::string(Interrupted(12.5).what()).find("t = 12.5 s"), std::string::npos);
}
