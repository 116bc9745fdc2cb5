/* The context's locks (roma/context.h's thread contract), over POSIX mutexes: glibc's C11
 * <threads.h> calls them internally, out of ThreadSanitizer's sight (make test-tsan). */
#ifndef ROMA_UTIL_MUTEX_H
#define ROMA_UTIL_MUTEX_H

#include <pthread.h>

typedef struct roma_mutex {
    pthread_mutex_t m;
} roma_mutex;

/* recursive: the same thread may lock it again (as many unlocks). Returns 0 on failure. */
static inline int roma_mutex_init(roma_mutex *mutex, int recursive)
{
    pthread_mutexattr_t attr;
    if (pthread_mutexattr_init(&attr) != 0)
        return 0;
    int ok = pthread_mutexattr_settype(&attr, recursive ? PTHREAD_MUTEX_RECURSIVE : PTHREAD_MUTEX_NORMAL) == 0 &&
             pthread_mutex_init(&mutex->m, &attr) == 0;
    pthread_mutexattr_destroy(&attr);
    return ok;
}

static inline void roma_mutex_destroy(roma_mutex *mutex)
{
    pthread_mutex_destroy(&mutex->m);
}

static inline void roma_mutex_lock(roma_mutex *mutex)
{
    pthread_mutex_lock(&mutex->m);
}

static inline void roma_mutex_unlock(roma_mutex *mutex)
{
    pthread_mutex_unlock(&mutex->m);
}

#endif /* ROMA_UTIL_MUTEX_H */
