// ParallelErrors carries an exception out of an OpenMP region: whatever
// threads throw and however many, the region ends normally and the first
// exception is rethrown after it with its type and message (an exception
// leaving a region calls std::terminate: the abort of exit 134).

#include "core/error.hpp"
#include "core/parallel.hpp"

#include <gtest/gtest.h>

#include <omp.h>

#include <new>
#include <string>

namespace core = lamina::core;

TEST(ParallelErrors, FirstExceptionLeavesTheRegionWithItsTypeAndMessage) {
  for (const int bad_every : {1, 7, 1000}) { // every item, some, one
    core::ParallelErrors errors;
    int after = 0; // the region's own code after the loop still runs
    int team = 0;
#pragma omp parallel num_threads(4) // a team of its own: the global setting stays
    {
#pragma omp single
      team = omp_get_num_threads();
#pragma omp for schedule(dynamic, 1)
      for (int i = 0; i < 1000; ++i)
        errors.run([&] {
          if (i % bad_every == bad_every - 1)
            throw lamina::Error("item " + std::to_string(i) + " refused", {"", 0, "x"});
        });
#pragma omp atomic
      ++after;
    }
    EXPECT_EQ(after, team);
    EXPECT_TRUE(errors.failed());
    try {
      errors.rethrow();
      FAIL() << "no exception";
    } catch (const lamina::Error& e) {
      EXPECT_NE(e.message().find(" refused"), std::string::npos) << e.what();
      EXPECT_EQ(e.context().key, "x");
    }
  }
}

TEST(ParallelErrors, AnyExceptionTypeAndNoneAtAll) {
  core::ParallelErrors errors;
#pragma omp parallel for
  for (int i = 0; i < 100; ++i)
    errors.run([&] {
      if (i == 50)
        throw std::bad_alloc();
    });
  EXPECT_THROW(errors.rethrow(), std::bad_alloc);

  core::ParallelErrors none;
  long sum = 0;
#pragma omp parallel for reduction(+ : sum)
  for (int i = 0; i < 100; ++i)
    none.run([&] { sum += i; });
  EXPECT_FALSE(none.failed());
  EXPECT_NO_THROW(none.rethrow());
  EXPECT_EQ(sum, 4950); // every item ran: 0 + 1 + ... + 99
}
