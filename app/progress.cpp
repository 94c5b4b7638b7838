// app/progress.cpp: terminal detection for progress lines.
#include "app/progress.h"

#include <cstdio>
#include <unistd.h>

namespace frontier::app
{

bool stderrIsTerminal()
{
    return isatty(fileno(stderr)) != 0;
}

} // namespace frontier::app
