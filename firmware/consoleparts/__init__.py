# The console's parts loaded on demand (more, selftestbus, selftestsweep): a folder of their own keeps
# the board's root directory short (each module import's littlefs lookups there cost a Pico's boot).
