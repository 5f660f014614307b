#pragma once
// WADO-RS of the image series whose original instances soiqd kept at import
// (server/app/kept_instances.h): the instances as they were received (or in Explicit VR Little
// Endian when the client asks for it), their metadata (DICOM JSON with the SOP Instance UIDs the
// SEGs soiq writes reference) and their frames uncompressed (dicom/instance_frames.h). What a
// viewer such as OHIF needs to open a series from soiqd alone. wado_handlers.cpp routes here every
// series that is not a structure's SEG or RT Structure Set, and a study's retrieval and metadata
// take both.
//
// Memory: a series or study is sent one instance at a time (chunked, each written before the next
// is read), each file's bytes reserved in the budget before it is read; metadata is small.

#include <string>
#include <vector>

#include "db/store_records.h"
#include "server/http/http_handlers.h"

namespace soiq::server::http {

// The kept instances of image series `series_uid` of study `study_uid`, or of one instance of it.
// NOT_FOUND saying why for an unknown series or instance, and for a series whose instances were not
// kept (soiqd --keep-instances off, or imported before soiq kept them: import it again).
Result<std::vector<db::InstanceRecord>> kept_series_instances(const AppEngines& e, const std::string& study_uid,
                                                              const std::string& series_uid,
                                                              const std::string& instance_uid);
// Every kept instance of the study's image series (empty when none).
Result<std::vector<db::InstanceRecord>> kept_study_instances(const AppEngines& e, const std::string& study_uid);

// One instance's metadata with its Pixel Data's BulkDataURI on this server.
std::string kept_instance_metadata(const HandlerContext& c, const std::string& study_uid,
                                   const db::InstanceRecord& instance);

// How the Accept header lets an original instance go out: as stored, in Explicit VR Little
// Endian, or not at all (406).
enum class InstanceSyntax { kAsStored, kExplicitLittleEndian, kNotAcceptable };
InstanceSyntax instance_syntax(const HttpRequest& req);

// A multipart/related answer of application/dicom parts: the kept instances, then `extra` (soiq's
// SEGs and RT Structure Sets, Explicit VR Little Endian), streamed when the request allows (GET),
// else whole.
Result<HttpReply> send_instances(const HandlerContext& c, const std::vector<db::InstanceRecord>& instances,
                                 std::vector<std::string> extra, InstanceSyntax syntax, const HttpRequest& req);

// GET .../instances/{uid}/frames/{list} and .../instances/{uid}/bulkdata of a kept instance.
Result<HttpReply> send_frames(const HandlerContext& c, const db::InstanceRecord& instance, const std::string& frames,
                              const HttpRequest& req);

}  // namespace soiq::server::http
