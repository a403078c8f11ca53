// render/interrupt.h: a signal is recorded, not acted on; the signals that follow the first
// at once (a group delivery) are ignored; nested scopes keep the first signal; the old
// handlers come back when the outermost scope ends.
#include "render/interrupt.h"

#include <signal.h>

#include <gtest/gtest.h>

namespace tessera {
namespace {

void (*current_handler(int sig))(int) {
    struct sigaction sa {};
    sigaction(sig, nullptr, &sa);
    return sa.sa_handler;
}

TEST(Interrupt, SignalsAreRecordedAndAPairDoesNotKill) {
    // As a terminal starts it: a test run in the background of a script inherits an
    // ignored SIGINT, which InterruptScope keeps ignored (AnIgnoredSigintStaysIgnored).
    const auto inherited = ::signal(SIGINT, SIG_DFL);
    const auto before = current_handler(SIGINT);
    {
        const InterruptScope scope;
        EXPECT_EQ(interrupt_signal(), 0);
        ::raise(SIGTERM);
        EXPECT_EQ(interrupt_signal(), SIGTERM);
        ::raise(SIGINT);  // within the grace time: ignored (the process would end here)
        ::raise(SIGINT);
        EXPECT_EQ(interrupt_signal(), SIGTERM);  // the first one is kept
        {
            const InterruptScope nested;  // e.g. a CheckpointSession inside the command's scope
            EXPECT_EQ(interrupt_signal(), SIGTERM);
        }
        EXPECT_NE(current_handler(SIGINT), before);
    }
    EXPECT_EQ(current_handler(SIGINT), before);
    {
        const InterruptScope fresh;
        EXPECT_EQ(interrupt_signal(), 0);  // a new outermost scope starts clean
    }
    ::signal(SIGINT, inherited);
}

// A closed terminal or ssh session (SIGHUP) stops a render cleanly, as Ctrl-C does; under
// nohup, which ignores it, it stays ignored.
TEST(Interrupt, SighupIsRecordedUnlessIgnored) {
    const auto inherited = ::signal(SIGHUP, SIG_DFL);  // a test run under nohup
    const auto before = current_handler(SIGHUP);
    {
        const InterruptScope scope;
        ::raise(SIGHUP);
        EXPECT_EQ(interrupt_signal(), SIGHUP);
    }
    EXPECT_EQ(current_handler(SIGHUP), before);
    ::signal(SIGHUP, SIG_IGN);
    {
        const InterruptScope scope;
        EXPECT_EQ(current_handler(SIGHUP), SIG_IGN);
        ::raise(SIGHUP);
        EXPECT_EQ(interrupt_signal(), 0);
    }
    ::signal(SIGHUP, inherited);
}

TEST(Interrupt, AnIgnoredSigintStaysIgnored) {
    const auto before = current_handler(SIGINT);
    ::signal(SIGINT, SIG_IGN);
    {
        const InterruptScope scope;
        EXPECT_EQ(current_handler(SIGINT), SIG_IGN);
        ::raise(SIGINT);
        EXPECT_EQ(interrupt_signal(), 0);
    }
    ::signal(SIGINT, before);
}

}  // namespace
}  // namespace tessera
