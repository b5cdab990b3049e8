// The test binary's main: doctest's, plus one rule. CTest runs each test case by name
// (--test-case=NAME); a name that selects nothing (CTest splits registered names at ';') would
// otherwise pass without running anything. Such a run fails here.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>
#include <cstring>

namespace {
int started = 0;

struct CountingListener : doctest::IReporter {
    explicit CountingListener(const doctest::ContextOptions&) {}
    void report_query(const doctest::QueryData&) override {}
    void test_run_start() override {}
    void test_run_end(const doctest::TestRunStats&) override {}
    void test_case_start(const doctest::TestCaseData&) override { ++started; }
    void test_case_reenter(const doctest::TestCaseData&) override {}
    void test_case_end(const doctest::CurrentTestCaseStats&) override {}
    void test_case_exception(const doctest::TestCaseException&) override {}
    void subcase_start(const doctest::SubcaseSignature&) override {}
    void subcase_end() override {}
    void log_assert(const doctest::AssertData&) override {}
    void log_message(const doctest::MessageData&) override {}
    void test_case_skipped(const doctest::TestCaseData&) override {}
};
REGISTER_LISTENER("counting", 1, CountingListener);
} // namespace

int main(int argc, char** argv) {
    doctest::Context context(argc, argv);
    const int result = context.run();
    if (context.shouldExit()) return result;
    bool filtered = false;
    for (int k = 1; k < argc; ++k)
        filtered = filtered || std::strncmp(argv[k], "--test-case=", 12) == 0 ||
                   std::strncmp(argv[k], "-tc=", 4) == 0;
    if (filtered && started == 0) {
        std::fprintf(stderr, "no test case matches the filter: a test name CTest split or "
                             "mangled (avoid ';' in TEST_CASE names)\n");
        return 1;
    }
    return result;
}
