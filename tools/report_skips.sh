#!/bin/sh
# Lists the tests of the last ctest run in build dir $1 that skipped (GTEST_SKIP: ctest marks them
# Skipped through gtest_discover_tests' SKIP_REGULAR_EXPRESSION), each with the reason it printed,
# so a check that did not run is never mistaken for one that passed.  Used by `make test`.
log="$1/Testing/Temporary/LastTest.log"
[ -f "$log" ] || exit 0
awk '
  /^[0-9]+\/[0-9]+ Test: / { name = $3; reason = ""; grab = 0 }
  grab && /^\[  SKIPPED \]/ { grab = 0 }
  grab { reason = reason (reason == "" ? "" : " ") $0 }
  /: Skipped$/ { grab = 1 }
  /^Skip regular expression found in output/ { n++; lines = lines sprintf("  %s: %s\n", name, reason) }
  END {
    if (n > 0) printf("make: %d test%s SKIPPED (counted in \"tests passed\" above, but not checked):\n%s", n, n == 1 ? "" : "s", lines)
  }' "$log"
