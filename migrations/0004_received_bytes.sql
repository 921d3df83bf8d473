-- The encoded DCCL bytes of each received message, on its "received"
-- event (NULL on every other kind). At start-up the duplicate filter is
-- filled again from the received events of its window, so that a message
-- sent again because its ACK was lost, while this node restarted, is not
-- passed on a second time (a command must not be carried out twice).
ALTER TABLE event_log ADD COLUMN encoded BLOB;
