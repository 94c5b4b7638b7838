// app/progress.h: whether progress lines go to the terminal.
#pragma once

namespace frontier::app
{

// Progress is shown only when stderr is a terminal (never in logs or pipes).
bool stderrIsTerminal();

} // namespace frontier::app
