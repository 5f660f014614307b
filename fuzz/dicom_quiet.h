#pragma once
// DCMTK logs every malformed element it meets to stderr; at fuzzing speed that is most of the time
// spent and all of the output. Errors still reach soiq as OFCondition, which is what is tested.

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/oflog/oflog.h>

namespace soiq::fuzz {

inline void quiet_dcmtk() { OFLog::configure(OFLogger::FATAL_LOG_LEVEL); }

}  // namespace soiq::fuzz
