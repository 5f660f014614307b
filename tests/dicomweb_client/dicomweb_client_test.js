// soiqd's DICOMweb driven by dicomweb-client, the DICOMweb library of OHIF, as a web viewer would:
// QIDO-RS with paging and includefield, WADO-RS of a structure's SEG (whose voxels must be those
// `soiq export-seg` writes), its metadata, its RT Structure Set beside it (written to SOIQ_OUT for
// run_test.sh to judge with pydicom), and STOW-RS of a series that soiq then holds.
// Run by run_test.sh, which starts soiqd and passes SOIQ_DICOMWEB, SOIQ_DATA, SOIQ_EXPORTED_SEG and
// SOIQ_OUT.
'use strict';
const test = require('node:test');
const assert = require('node:assert/strict');
const fs = require('node:fs');
const path = require('node:path');
global.XMLHttpRequest = require('xhr2');  // dicomweb-client is written for browsers
const { api } = require('dicomweb-client');

const client = new api.DICOMwebClient({ url: process.env.SOIQ_DICOMWEB });
const data = process.env.SOIQ_DATA;

const value = (item, tag) => (item[tag] && item[tag].Value ? item[tag].Value[0] : undefined);

// The Pixel Data of an Explicit VR Little Endian Part 10 file: (7FE0,0010) OB, then a 32-bit length.
function pixelData(bytes) {
  const b = Buffer.from(bytes);
  const tag = Buffer.from([0xe0, 0x7f, 0x10, 0x00, 0x4f, 0x42, 0x00, 0x00]);
  const at = b.lastIndexOf(tag);
  assert.ok(at > 0, 'no Pixel Data element');
  const length = b.readUInt32LE(at + 8);
  return b.subarray(at + 12, at + 12 + length);
}

function files(folder) {
  const out = [];
  for (const e of fs.readdirSync(folder, { withFileTypes: true })) {
    const p = path.join(folder, e.name);
    if (e.isDirectory()) out.push(...files(p));
    else if (p.endsWith('.dcm')) out.push(p);
  }
  return out.sort();
}

test('QIDO-RS lists the studies, pages them and includes fields on request', async () => {
  const studies = await client.searchForStudies();
  assert.equal(studies.length, 2);
  const first = await client.searchForStudies({ queryParams: { limit: 1, offset: 0 } });
  const second = await client.searchForStudies({ queryParams: { limit: 1, offset: 1 } });
  assert.deepEqual([value(first[0], '0020000D'), value(second[0], '0020000D')],
                   studies.map((s) => value(s, '0020000D')));
  const described = await client.searchForStudies({
    queryParams: { PatientID: 'STS_002', includefield: 'StudyDescription' },
  });
  assert.equal(described.length, 1);
  assert.ok('00081030' in described[0]);
  assert.equal(value(described[0], '00100010').Alphabetic, 'STS_002');
});

test('WADO-RS gives the SEG of a structure with the voxels soiq export-seg writes', async () => {
  const [study] = await client.searchForStudies({ queryParams: { PatientID: 'STS_002' } });
  const studyInstanceUID = value(study, '0020000D');
  const series = await client.searchForSeries({ studyInstanceUID });
  assert.deepEqual(series.map((s) => value(s, '00080060')), ['CT', 'SEG', 'RTSTRUCT']);
  const seriesInstanceUID = value(series[1], '0020000E');
  const instances = await client.retrieveSeries({ studyInstanceUID, seriesInstanceUID });
  assert.equal(instances.length, 1);
  const exported = fs.readFileSync(process.env.SOIQ_EXPORTED_SEG);
  assert.ok(pixelData(instances[0]).equals(pixelData(exported)), 'the SEG differs from the exported one');
  const metadata = await client.retrieveSeriesMetadata({ studyInstanceUID, seriesInstanceUID });
  assert.equal(value(metadata[0], '0020000E'), seriesInstanceUID);
  assert.match(metadata[0]['7FE00010'].BulkDataURI, /\/bulkdata$/);
  fs.writeFileSync(path.join(process.env.SOIQ_OUT, 'seg.dcm'), Buffer.from(instances[0]));
});

test('WADO-RS gives the RT Structure Set of the structure beside its SEG', async () => {
  const [study] = await client.searchForStudies({ queryParams: { PatientID: 'STS_002' } });
  const studyInstanceUID = value(study, '0020000D');
  const [series] = await client.searchForSeries({ studyInstanceUID, queryParams: { Modality: 'RTSTRUCT' } });
  const seriesInstanceUID = value(series, '0020000E');
  assert.equal(value(series, '00080060'), 'RTSTRUCT');
  const [listed] = await client.searchForInstances({ studyInstanceUID, seriesInstanceUID });
  assert.equal(value(listed, '00080016'), '1.2.840.10008.5.1.4.1.1.481.3');
  const instances = await client.retrieveSeries({ studyInstanceUID, seriesInstanceUID });
  assert.equal(instances.length, 1);
  const sopInstanceUID = value(listed, '00080018');
  const again = await client.retrieveInstance({ studyInstanceUID, seriesInstanceUID, sopInstanceUID });
  assert.ok(Buffer.from(again).equals(Buffer.from(instances[0])), 'the RT Structure Set differs the second time');
  const [metadata] = await client.retrieveInstanceMetadata({ studyInstanceUID, seriesInstanceUID, sopInstanceUID });
  assert.equal(value(metadata, '00080060'), 'RTSTRUCT');
  assert.equal(value(value(metadata, '30060020'), '30060026'), 'GTV_Mass_CT');
  const all = await client.retrieveStudyMetadata({ studyInstanceUID });
  assert.equal(all.filter((m) => value(m, '00080060') === 'RTSTRUCT').length, 1);
  fs.writeFileSync(path.join(process.env.SOIQ_OUT, 'rtstruct.dcm'), Buffer.from(instances[0]));
});

// The size of a PNG from its IHDR, or of a JPEG from its first start-of-frame marker. dicomweb-client
// hands a rendered answer over as a list of one ArrayBuffer.
function pictureSize(answer) {
  assert.ok(Array.isArray(answer) && answer.length === 1, 'not one picture');
  const b = Buffer.from(answer[0]);
  if (b.subarray(0, 8).equals(Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a])))
    return { type: 'png', width: b.readUInt32BE(16), height: b.readUInt32BE(20) };
  assert.ok(b[0] === 0xff && b[1] === 0xd8, 'neither PNG nor JPEG');
  for (let at = 2; at + 9 < b.length;) {
    const marker = b[at + 1];
    if (marker >= 0xc0 && marker <= 0xc2) return { type: 'jpeg', height: b.readUInt16BE(at + 5), width: b.readUInt16BE(at + 7) };
    at += 2 + b.readUInt16BE(at + 2);
  }
  assert.fail('a JPEG without a frame header');
}

test('WADO-RS renders the SEG over its CT slice and gives thumbnails in the viewport asked', async () => {
  const [study] = await client.searchForStudies({ queryParams: { PatientID: 'STS_002' } });
  const studyInstanceUID = value(study, '0020000D');
  const series = await client.searchForSeries({ studyInstanceUID });
  const seriesInstanceUID = value(series.find((s) => value(s, '00080060') === 'SEG'), '0020000E');
  const [instance] = await client.searchForInstances({ studyInstanceUID, seriesInstanceUID });
  const sopInstanceUID = value(instance, '00080018');
  const ids = { studyInstanceUID, seriesInstanceUID, sopInstanceUID };
  const png = await client.retrieveInstanceRendered({ ...ids, mediaTypes: [{ mediaType: 'image/png' }] });
  assert.equal(pictureSize(png).type, 'png');
  const frame = await client.retrieveInstanceFramesRendered({
    ...ids, frameNumbers: [1], mediaTypes: [{ mediaType: 'image/jpeg' }], queryParams: { window: '40,400' },
  });
  assert.equal(pictureSize(frame).type, 'jpeg');
  const thumbnail = await client.retrieveInstanceThumbnail({
    ...ids, mediaTypes: [{ mediaType: 'image/jpeg' }], queryParams: { viewport: '96,64' },
  });
  const size = pictureSize(thumbnail);
  assert.ok(size.width <= 96 && size.height <= 64 && (size.width === 96 || size.height === 64), JSON.stringify(size));
  await assert.rejects(client.retrieveInstanceRendered({ ...ids, mediaTypes: [{ mediaType: 'image/png' }],
                                                          queryParams: { annotation: 'patient' } }),
                       (e) => e.status === 400);
});

test('STOW-RS stores a series that QIDO-RS then lists', async () => {
  const datasets = files(path.join(data, 'sts/STS_002/dicom/PET'))
    .map((f) => { const b = fs.readFileSync(f); return b.buffer.slice(b.byteOffset, b.byteOffset + b.length); });
  const response = await client.storeInstances({ datasets });
  const stored = JSON.parse(Buffer.from(response).toString())['00081199'].Value;
  assert.equal(stored.length, datasets.length);
  const [study] = await client.searchForStudies({ queryParams: { PatientID: 'STS_002' } });
  assert.deepEqual(study['00080061'].Value, ['CT', 'PT', 'RTSTRUCT', 'SEG']);
});
