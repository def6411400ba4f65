#include "OutputLock.h"

#include "model/Error.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace netsculpt::cli {

OutputLock::OutputLock(const std::filesystem::path& folder) {
    const std::filesystem::path file = folder / kRunLockName;
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
        throw UserError("cannot open " + file.string() +
                        " to hold the output folder: " + std::strerror(errno));
    int result = 0;
    while ((result = ::flock(fd_, LOCK_EX | LOCK_NB)) != 0 && errno == EINTR) {
    }
    if (result == 0 || errno != EWOULDBLOCK)
        return;
    ::close(fd_);
    fd_ = -1;
    throw UserError("the output folder " + folder.string() +
                    " is in use by another netsculpt run (it holds " + file.string() +
                    "); two runs in one folder would mix their journals and files: wait for it "
                    "to end, or give this run another --out");
}

OutputLock::~OutputLock() {
    if (fd_ >= 0)
        ::close(fd_);
}

} // namespace netsculpt::cli
