#pragma once
// Checks that a call throws a given meshquilt error type whose message names what it should.

#include <gtest/gtest.h>

#include <exception>
#include <functional>
#include <string>
#include <vector>

namespace meshquilt::test {

/// Runs `f`, which must throw E with a message containing every fragment.
template <class E>
::testing::AssertionResult throws_with(const std::function<void()>& f, const std::vector<std::string>& fragments) {
    try {
        f();
    } catch (const E& e) {
        const std::string what = e.what();
        for (const std::string& frag : fragments)
            if (what.find(frag) == std::string::npos)
                return ::testing::AssertionFailure() << "message \"" << what << "\" lacks \"" << frag << "\"";
        return ::testing::AssertionSuccess();
    } catch (const std::exception& e) {
        return ::testing::AssertionFailure() << "threw the wrong type: " << e.what();
    }
    return ::testing::AssertionFailure() << "did not throw";
}

}  // namespace meshquilt::test
