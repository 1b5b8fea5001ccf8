# Sums `strace -f -T` output by system call and, for ioctl, by request: count, total seconds,
# mean microseconds. Calls split across lines by another thread's (<unfinished ...> and
# <... resumed>) are joined by thread id.
function record(req, line) {
    if (match(line, /<[0-9.]+>$/)) {
        t = substr(line, RSTART + 1, RLENGTH - 2); n[req]++; s[req] += t
    }
}
{
    if (match($0, /(ioctl|mmap|munmap|madvise|mprotect)\(/)) {
        call = substr($0, RSTART, RLENGTH - 1); req = call
        if (call == "ioctl" && match($0, /_IOC\([^)]*\)/)) req = "ioctl " substr($0, RSTART, RLENGTH)
        if ($0 ~ /<unfinished \.\.\.>$/) pending[$1] = req; else record(req, $0)
    } else if ($0 ~ /<\.\.\. [a-z]+ resumed>/ && ($1 in pending)) {
        record(pending[$1], $0); delete pending[$1]
    }
}
END { for (r in n) printf "%8d %9.3f %9.1f  %s\n", n[r], s[r], s[r] / n[r] * 1e6, r }
