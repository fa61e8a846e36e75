-- A job store of schema version 1, as tessera-coordinator at commit bcf043b wrote it: one job
-- (16x12, queued: no worker was connected), printed by `sqlite3 tessera.db .dump`. The dump
-- leaves out the header's pragmas, set here first as that coordinator set them. Its bundle
-- file is bundles/<hash> beside this file. Frozen: tests/service/job_database_test.cpp
-- migrates it, as a newer coordinator would.
PRAGMA auto_vacuum = INCREMENTAL;
PRAGMA journal_mode = WAL;
PRAGMA application_id = 1413829459;
PRAGMA user_version = 1;
PRAGMA foreign_keys=OFF;
BEGIN TRANSACTION;
CREATE TABLE bundles (
  hash TEXT PRIMARY KEY,
  bytes INTEGER NOT NULL
);
INSERT INTO bundles VALUES('fea1691dd3fd748d24beb68ccfe437d92305c5a9f9ceb411a864fe70bcd12103',102);
CREATE TABLE jobs (
  id INTEGER PRIMARY KEY AUTOINCREMENT,
  bundle_hash TEXT NOT NULL REFERENCES bundles(hash),
  spec TEXT NOT NULL,
  width INTEGER NOT NULL, height INTEGER NOT NULL, passes INTEGER NOT NULL,
  progressive INTEGER NOT NULL, unit_order TEXT NOT NULL, preview TEXT NOT NULL,
  unit_pixels INTEGER NOT NULL,
  priority INTEGER NOT NULL,
  effects TEXT NOT NULL, warnings TEXT NOT NULL,
  seconds_per_pixel_pass REAL NOT NULL, uncalibrated_prediction REAL, predicted_seconds REAL,
  prediction_threads INTEGER NOT NULL,
  state TEXT NOT NULL, error TEXT NOT NULL,
  created_us INTEGER NOT NULL, finished_us INTEGER
);
INSERT INTO jobs VALUES(1,'fea1691dd3fd748d24beb68ccfe437d92305c5a9f9ceb411a864fe70bcd12103','{"aa":1,"brightness":1.0,"bvh":true,"cone_samples":9,"height":12,"jitter":1.0,"normalize":false,"passes":1,"seed":0,"shadow_jitter":0.2,"shadows":"hard","stochastic":false,"time_samples":0,"width":16}',16,12,1,1,'centre','anchor',16384,1,'["hard_shadows"]','[]',2.1017578124999998947e-07,NULL,NULL,0,'queued','',1795746077456566,NULL);
CREATE TABLE results (
  job_id INTEGER NOT NULL REFERENCES jobs(id) ON DELETE CASCADE,
  sequence INTEGER NOT NULL,
  unit INTEGER NOT NULL,
  payload BLOB NOT NULL,
  stats TEXT NOT NULL,
  worker TEXT NOT NULL,
  PRIMARY KEY (job_id, sequence)
);
CREATE TABLE images (
  job_id INTEGER NOT NULL REFERENCES jobs(id) ON DELETE CASCADE,
  name TEXT NOT NULL,
  bytes INTEGER NOT NULL,
  PRIMARY KEY (job_id, name)
);
DELETE FROM sqlite_sequence;
INSERT INTO sqlite_sequence VALUES('jobs',1);
CREATE INDEX jobs_by_finish ON jobs(finished_us) WHERE finished_us IS NOT NULL;
COMMIT;
