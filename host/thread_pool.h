// The thread pool lives in ref/ (ref/thread_pool.h), below both host/ and sysc/, since the fast runner
// (ref/fast.h) keeps one; host code may keep including it from here.
#pragma once

#include "ref/thread_pool.h"
